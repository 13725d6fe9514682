#include "tools/bench/sampled_envelope.h"

#include <algorithm>
#include <cmath>

namespace metrosync {

EnvelopeRecorder::EnvelopeRecorder(double epsilon, std::vector<bool> active, RunSink& sink)
    : epsilon_(epsilon),
      active_(std::move(active)),
      sink_(sink),
      n_(static_cast<int>(active_.size())),
      sum_A_(n_, 0.0),
      sum_er_(n_, 0.0),
      sum_ei_(n_, 0.0),
      unwrap_(n_ > 1 ? n_ - 1 : 0),
      trailing_(3 * n_) {
  prev_.resize(n_);
  cur_ = prev_;
}

void EnvelopeRecorder::eval(double t, const double* theta, const double* thetadot,
                            Values& out) const {
  const double cr = std::cos(t), ci = -std::sin(t);  // exp(-i t)
  double* __restrict A = out.A.data();
  double* __restrict er = out.er.data();
  double* __restrict ei = out.ei.data();
  for (int i = 0; i < n_; ++i) {
    // A_i = |(theta, thetadot)| (scaled: O(1), no overflow to guard against as hypot does);
    // exp(i atan2(theta, thetadot)) = (thetadot + i theta) / A, turned by exp(-i t)
    const double th = theta[i], w = thetadot[i];
    const double a = std::sqrt(th * th + w * w);
    // the divisions on a safe divisor, then a select: vectorizable (a division is not
    // speculated by the compiler)
    const double d = a > 0 ? a : 1.0, ur0 = w / d, ui0 = th / d;
    const double ur = a > 0 ? ur0 : 1.0, ui = a > 0 ? ui0 : 0.0;
    A[i] = a;
    er[i] = ur * cr - ui * ci;
    ei[i] = ur * ci + ui * cr;
  }
  for (int i = 0; i < n_; ++i) {
    if (active_[i]) continue;  // a locked metronome: A = 0, phase 0
    A[i] = 0.0;
    er[i] = 1.0;
    ei[i] = 0.0;
  }
}

void EnvelopeRecorder::sample(double t, const double* theta, const double* thetadot) {
  eval(t, theta, thetadot, cur_);
  keepTrailing(t);
  if (!have_prev_) {  // the start's envelope: the instantaneous A and phases
    EnvelopeRow start;
    start.tau = epsilon_ * t;
    start.A = cur_.A;
    emit(std::move(start), cur_.er, cur_.ei);
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
            b.er[i] = a.er[i] + w * (cur_.er[i] - a.er[i]);
            b.ei[i] = a.ei[i] + w * (cur_.ei[i] - a.ei[i]);
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
  const double half = 0.5 * h;
  for (int i = 0; i < n_; ++i) {
    sum_A_[i] += half * (a.A[i] + b.A[i]);
    sum_er_[i] += half * (a.er[i] + b.er[i]);
    sum_ei_[i] += half * (a.ei[i] + b.ei[i]);
  }
  covered_ += h;
}

void EnvelopeRecorder::closePeriod() {
  EnvelopeRow row;
  row.tau = envelopeTau(epsilon_, period_);
  row.A.resize(n_);
  const double len = covered_ > 0 ? covered_ : 1.0;
  for (int i = 0; i < n_; ++i) row.A[i] = sum_A_[i] / len;
  emit(std::move(row), sum_er_, sum_ei_);
  for (auto* sum : {&sum_A_, &sum_er_, &sum_ei_}) std::fill(sum->begin(), sum->end(), 0.0);
  covered_ = 0.0;
  ++period_;
}

// Completes a row with A set: psi_j = phi_1 - phi_j from the phases' sums (unit complex numbers,
// averaged: only their direction counts), unwrapped against the rows before, and r.
void EnvelopeRecorder::emit(EnvelopeRow row, const std::vector<double>& phase_re,
                            const std::vector<double>& phase_im) {
  std::vector<double> phi(n_);
  for (int i = 0; i < n_; ++i) phi[i] = active_[i] ? std::atan2(phase_im[i], phase_re[i]) : 0.0;
  row.psi.clear();
  for (int j = 1; j < n_; ++j) row.psi.push_back(unwrap_[j - 1](phi[0] - phi[j]));
  row.r = orderParameter(row.A, row.psi);
  sink_.envelopeRow(row);
  last_row_ = std::move(row);
}

// Keeps the samples of [t - 2 pi, t] and the last one before (to interpolate at t - 2 pi).
void EnvelopeRecorder::keepTrailing(double t) {
  while (trailing_.size() > 1 && trailing_.time(1) <= t - kTwoPi) trailing_.popFront();
  trailing_.push(t, {cur_.A.data(), cur_.er.data(), cur_.ei.data()}, {n_, n_, n_});
}

void EnvelopeRecorder::trailingValues(size_t k, Values& out) const {
  const double* v = trailing_.values(k);
  out.A.assign(v, v + n_);
  out.er.assign(v + n_, v + 2 * n_);
  out.ei.assign(v + 2 * n_, v + 3 * n_);
}

EnvelopeRow EnvelopeRecorder::finish() {
  if (trailing_.empty()) return {};
  const double t_end = trailing_.time(trailing_.size() - 1);
  const double t_from = std::max(trailing_.time(0), t_end - kTwoPi);
  Values a, b;
  trailingValues(0, a);
  double ta = trailing_.time(0);
  std::vector<double> sum_A(n_, 0.0), sum_er(n_, 0.0), sum_ei(n_, 0.0);
  for (size_t k = 1; k < trailing_.size(); ++k) {
    const double tb = trailing_.time(k);
    trailingValues(k, b);
    if (tb > t_from && ta < t_from) {  // the window starts inside [ta, tb]: linear interpolation
      const double w = (t_from - ta) / (tb - ta);
      for (int i = 0; i < n_; ++i) {
        a.A[i] += w * (b.A[i] - a.A[i]);
        a.er[i] += w * (b.er[i] - a.er[i]);
        a.ei[i] += w * (b.ei[i] - a.ei[i]);
      }
      ta = t_from;
    }
    if (ta >= t_from) {  // the trapezoid rule, as for the period rows
      for (int i = 0; i < n_; ++i) {
        sum_A[i] += 0.5 * (tb - ta) * (a.A[i] + b.A[i]);
        sum_er[i] += 0.5 * (tb - ta) * (a.er[i] + b.er[i]);
        sum_ei[i] += 0.5 * (tb - ta) * (a.ei[i] + b.ei[i]);
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
    if (final_span_ > 0) continue;
    sum_er[i] = a.er[i];
    sum_ei[i] = a.ei[i];
  }
  emit(std::move(row), sum_er, sum_ei);
  return last_row_;
}

}  // namespace metrosync
