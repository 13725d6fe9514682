#include "sim/record/envelope_recorder.h"

#include <cmath>

namespace metrosync {

EnvelopeRecorder::EnvelopeRecorder(double epsilon, std::vector<bool> active, RunSink& sink)
    : epsilon_(epsilon),
      active_(std::move(active)),
      sink_(sink),
      n_(static_cast<int>(active_.size())),
      sum_A_(n_, 0.0),
      sum_e_(n_, 0.0),
      unwrap_(n_ > 1 ? n_ - 1 : 0) {
  prev_.A.resize(n_);
  prev_.e.resize(n_);
  cur_ = prev_;
}

void EnvelopeRecorder::eval(double t, const double* theta, const double* thetadot,
                            Values& out) const {
  const std::complex<double> rot(std::cos(t), -std::sin(t));  // exp(-i t)
  for (int i = 0; i < n_; ++i) {
    if (!active_[i]) {
      out.A[i] = 0.0;
      out.e[i] = 1.0;
      continue;
    }
    const double a = std::hypot(theta[i], thetadot[i]);
    out.A[i] = a;
    // exp(i atan2(theta, thetadot)) = (thetadot + i theta) / A
    const std::complex<double> u =
        a > 0 ? std::complex<double>(thetadot[i] / a, theta[i] / a) : std::complex<double>(1, 0);
    out.e[i] = u * rot;
  }
}

void EnvelopeRecorder::sample(double t, const double* theta, const double* thetadot) {
  eval(t, theta, thetadot, cur_);
  if (have_prev_) {
    if (t <= nextBoundary()) {
      // the usual case: the whole interval lies in the current period
      integrate(t - t_prev_, prev_, cur_);
      if (t == nextBoundary()) closePeriod();
    } else {
      // integrate [t_prev_, t] period by period (linear interpolation at a boundary inside)
      double ta = t_prev_;
      Values a = prev_;
      while (t > ta) {
        const double boundary = nextBoundary();
        const double tb = std::min(t, boundary);
        Values b = cur_;
        if (tb < t) {
          const double w = (tb - ta) / (t - ta);
          for (int i = 0; i < n_; ++i) {
            b.A[i] = a.A[i] + w * (cur_.A[i] - a.A[i]);
            b.e[i] = a.e[i] + w * (cur_.e[i] - a.e[i]);
          }
        }
        integrate(tb - ta, a, b);
        ta = tb;
        a = b;
        if (tb >= boundary) closePeriod();
      }
    }
  } else if (t >= nextBoundary()) {
    closePeriod();
  }
  std::swap(prev_, cur_);
  t_prev_ = t;
  have_prev_ = true;
}

void EnvelopeRecorder::integrate(double h, const Values& a, const Values& b) {
  for (int i = 0; i < n_; ++i) {
    sum_A_[i] += 0.5 * h * (a.A[i] + b.A[i]);
    sum_e_[i] += 0.5 * h * (a.e[i] + b.e[i]);
  }
  covered_ += h;
}

void EnvelopeRecorder::closePeriod() {
  EnvelopeRow row;
  row.tau = envelopeTau(epsilon_, period_);
  row.A.resize(n_);
  std::vector<double> phi(n_);
  const double len = covered_ > 0 ? covered_ : 1.0;
  for (int i = 0; i < n_; ++i) {
    row.A[i] = sum_A_[i] / len;
    phi[i] = active_[i] ? std::arg(sum_e_[i]) : 0.0;
    sum_A_[i] = 0.0;
    sum_e_[i] = 0.0;
  }
  for (int j = 1; j < n_; ++j) row.psi.push_back(unwrap_[j - 1](phi[0] - phi[j]));
  row.r = orderParameter(row.A, row.psi);  // of the period's averages
  covered_ = 0.0;
  ++period_;
  sink_.envelopeRow(row);
  last_row_ = std::move(row);
}

}  // namespace metrosync
