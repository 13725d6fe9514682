#include "sim/record/envelope_recorder.h"

#include <algorithm>
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
  keepTrailing(t);
  if (!have_prev_) {  // the start's envelope: the instantaneous A and phases
    EnvelopeRow start;
    start.tau = epsilon_ * t;
    start.A = cur_.A;
    emit(std::move(start), cur_.e);
  }
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
  const double len = covered_ > 0 ? covered_ : 1.0;
  for (int i = 0; i < n_; ++i) row.A[i] = sum_A_[i] / len;
  emit(std::move(row), sum_e_);
  std::fill(sum_A_.begin(), sum_A_.end(), 0.0);
  std::fill(sum_e_.begin(), sum_e_.end(), std::complex<double>(0.0));
  covered_ = 0.0;
  ++period_;
}

// Completes a row with A set: psi_j = phi_1 - phi_j from the phases' sums (unit complex numbers,
// averaged: only their direction counts), unwrapped against the rows before, and r.
void EnvelopeRecorder::emit(EnvelopeRow row, const std::vector<std::complex<double>>& phase_sum) {
  std::vector<double> phi(n_);
  for (int i = 0; i < n_; ++i) phi[i] = active_[i] ? std::arg(phase_sum[i]) : 0.0;
  row.psi.clear();
  for (int j = 1; j < n_; ++j) row.psi.push_back(unwrap_[j - 1](phi[0] - phi[j]));
  row.r = orderParameter(row.A, row.psi);
  sink_.envelopeRow(row);
  last_row_ = std::move(row);
}

// Keeps the samples of [t - 2 pi, t] and the last one before (to interpolate at t - 2 pi).
void EnvelopeRecorder::keepTrailing(double t) {
  std::pair<double, Values> entry;  // reuses the storage of a dropped sample
  while (trailing_.size() > 1 && trailing_[1].first <= t - kTwoPi) {
    entry = std::move(trailing_.front());
    trailing_.pop_front();
  }
  entry.first = t;
  entry.second.A = cur_.A;
  entry.second.e = cur_.e;
  trailing_.push_back(std::move(entry));
}

EnvelopeRow EnvelopeRecorder::finish() {
  if (trailing_.empty()) return {};
  const double t_end = trailing_.back().first;
  const double t_from = std::max(trailing_.front().first, t_end - kTwoPi);
  Values a = trailing_.front().second, b;
  double ta = trailing_.front().first;
  std::vector<double> sum_A(n_, 0.0);
  std::vector<std::complex<double>> sum_e(n_, 0.0);
  for (size_t k = 1; k < trailing_.size(); ++k) {
    const double tb = trailing_[k].first;
    b = trailing_[k].second;
    if (tb > t_from && ta < t_from) {  // the window starts inside [ta, tb]: linear interpolation
      const double w = (t_from - ta) / (tb - ta);
      for (int i = 0; i < n_; ++i) {
        a.A[i] += w * (b.A[i] - a.A[i]);
        a.e[i] += w * (b.e[i] - a.e[i]);
      }
      ta = t_from;
    }
    if (ta >= t_from) {  // the trapezoid rule, as for the period rows
      for (int i = 0; i < n_; ++i) {
        sum_A[i] += 0.5 * (tb - ta) * (a.A[i] + b.A[i]);
        sum_e[i] += 0.5 * (tb - ta) * (a.e[i] + b.e[i]);
      }
    }
    a = b;
    ta = tb;
  }
  final_span_ = t_end - t_from;
  EnvelopeRow row;
  row.tau = epsilon_ * t_end;
  row.A.resize(n_);
  for (int i = 0; i < n_; ++i) {
    // one sample only (a run of length 0): the instantaneous envelope
    row.A[i] = final_span_ > 0 ? sum_A[i] / final_span_ : a.A[i];
    if (!(final_span_ > 0)) sum_e[i] = a.e[i];
  }
  emit(std::move(row), sum_e);
  return last_row_;
}

}  // namespace metrosync
