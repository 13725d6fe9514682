#include "sim/ode/rk_stepper.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace metrosync::ode {

namespace {

using Weights = std::vector<std::pair<int, double>>;

Weights nonzero(const std::vector<double>& w, int count) {
  Weights out;
  for (int l = 0; l < count; ++l)
    if (w[l] != 0.0) out.emplace_back(l, w[l]);
  return out;
}

}  // namespace

RkStepper::RkStepper(const RkTableau& tableau, int dim, OdeRhs& rhs)
    : tab_(tableau),
      dim_(dim),
      rhs_(rhs),
      atol_(dim, 0.0),
      y_(dim, 0.0),
      y1_(dim, 0.0),
      tmp_(dim, 0.0),
      k_(static_cast<size_t>(tableau.dense_stages) * dim, 0.0),
      w_() {
  if (!tab_.fsal) throw std::invalid_argument("RkStepper: the method must be FSAL");
  for (int j = 0; j < tab_.dense_stages; ++j) a_rows_.push_back(nonzero(tab_.a[j], j));
  b_ = nonzero(tab_.b, tab_.stages);
  e_ = nonzero(tab_.e, tab_.stages);
  for (int j = 0; j < tab_.dense_stages; ++j) {
    if (nonzero(tab_.p[j], tab_.dense_degree).empty()) continue;
    dense_stage_.push_back(j);
    dense_p_.insert(dense_p_.end(), tab_.p[j].begin(), tab_.p[j].end());
  }
  // degree-major copies for stageWeights, zero-padded to kPadRows rows when they fit: p_rq, and
  // (q + 1) p_rq for the rate
  const int rows = static_cast<int>(dense_stage_.size()), deg = tab_.dense_degree;
  padded_rows_ = rows <= kPadRowsSmall ? kPadRowsSmall : (rows <= kPadRows ? kPadRows : rows);
  w_.assign(padded_rows_, 0.0);  // padded: hornerRows stores whole vectors (the pads are 0)
  dense_pt_.assign(static_cast<size_t>(padded_rows_) * deg, 0.0);
  dense_rate_pt_ = dense_pt_;
  for (int r = 0; r < rows; ++r)
    for (int q = 0; q < deg; ++q) {
      const double v = dense_p_[static_cast<size_t>(r) * deg + q];
      dense_pt_[static_cast<size_t>(q) * padded_rows_ + r] = v;
      dense_rate_pt_[static_cast<size_t>(q) * padded_rows_ + r] = (q + 1) * v;
    }
}

void RkStepper::setTolerances(double rtol, std::vector<double> atol) {
  rtol_ = rtol;
  atol_ = std::move(atol);
}

namespace {

// out = y + sum_t hw_t ks_t with the term count known at compile time: one pass over the
// components (vectorized), the terms added in the same order as a stage-by-stage sum, so the
// result is the same to the last bit.
template <int T>
void combineTerms(const double* __restrict y, const double* const* ks, const double* hw, int dim,
                  double* __restrict out) {
  for (int k = 0; k < dim; ++k) {
    double acc = y[k];
    for (int t = 0; t < T; ++t) acc += hw[t] * ks[t][k];
    out[k] = acc;
  }
}

using CombineFn = void (*)(const double*, const double* const*, const double*, int, double*);

template <int... T>
constexpr std::array<CombineFn, sizeof...(T)> combineTable(std::integer_sequence<int, T...>) {
  return {&combineTerms<T>...};
}

constexpr int kMaxTerms = 16;  // the most nonzero weights of any row (verner76: 15)
constexpr auto kCombine = combineTable(std::make_integer_sequence<int, kMaxTerms + 1>{});

}  // namespace

void RkStepper::combine(const Weights& w, double h, double* __restrict out) const {
  const int terms = static_cast<int>(w.size());
  if (terms > kMaxTerms) throw std::logic_error("RkStepper::combine: too many terms");
  const double* ks[kMaxTerms];
  double hw[kMaxTerms];
  for (int t = 0; t < terms; ++t) {
    ks[t] = stage(w[t].first);
    hw[t] = h * w[t].second;
  }
  kCombine[terms](y_.data(), ks, hw, dim_, out);
}

void RkStepper::restart(double t, const double* y) {
  w_th_ = -1.0;
  t_ = t;
  h_ = 0.0;
  std::copy(y, y + dim_, y_.begin());
  rhs_.eval(y_.data(), stage(0));
  ++evals_;
}

double RkStepper::attempt(double h) {
  w_th_ = -1.0;
  h_ = h;
  extra_stages_ = false;
  const int s = tab_.stages;
  // stages 1 .. s-2; s-1 is the FSAL stage, f(y1)
  for (int j = 1; j < s - 1; ++j) {
    combine(a_rows_[j], h, tmp_.data());
    rhs_.eval(tmp_.data(), stage(j));
  }
  combine(b_, h, y1_.data());
  rhs_.eval(y1_.data(), stage(s - 1));
  evals_ += s - 1;
  // error norm: the worst component relative to its tolerance, or the root mean square
  // the embedded difference sum_l e_l k_l, stage by stage (vectorized over the components; per
  // component the same sums in the same order as one component at a time)
  double* __restrict diff = tmp_.data();
  for (int k = 0; k < dim_; ++k) diff[k] = 0.0;
  for (const auto& [l, el] : e_) {
    const double* __restrict kl = stage(l);
    for (int k = 0; k < dim_; ++k) diff[k] += el * kl[k];
  }
  double err = 0.0, sum = 0.0;
  int counted = 0;
  for (int k = 0; k < dim_; ++k) {
    if (atol_[k] < 0) continue;
    const double sc = atol_[k] + rtol_ * std::max(std::abs(y_[k]), std::abs(y1_[k]));
    const double r = std::abs(h * diff[k]) / sc;
    if (!(r <= err)) err = r;  // a NaN wins: a step that produced one is never accepted
    sum += r * r;
    ++counted;
  }
  if (norm_ == Norm::Rms && std::isfinite(err)) err = counted > 0 ? std::sqrt(sum / counted) : 0.0;
  if (!std::isfinite(err)) err = std::numeric_limits<double>::infinity();
  return err;
}

void RkStepper::advance() {
  w_th_ = -1.0;
  t_ += h_;
  std::swap(y_, y1_);
  std::copy(stage(tab_.stages - 1), stage(tab_.stages - 1) + dim_, stage(0));
  h_ = 0.0;
}

double RkStepper::nextStepSize(double h, double err, bool accepted) {
  // Hairer's DOPRI5 controller: safety 0.9, the step changes by a factor in [0.2, 10]
  const double beta = tab_.pi_beta;
  const double expo = 1.0 / (tab_.error_order + 1) - 0.75 * beta;
  const double fac11 = std::pow(std::max(err, 1e-300), expo);
  if (accepted) {
    double fac = fac11 / std::pow(err_old_, beta) / 0.9;
    fac = std::clamp(fac, 0.1, 5.0);
    err_old_ = std::max(err, 1e-4);
    return h / fac;
  }
  return h / std::min(5.0, fac11 / 0.9);
}

double RkStepper::initialStepSize(double h_max) {
  // d0 = ||y0||, d1 = ||f(y0)||, d2 = ||f'|| estimated by a trial Euler step; RMS norms in the
  // units of the error target
  auto norm = [&](auto&& value) {
    double sum = 0.0;
    int counted = 0;
    for (int k = 0; k < dim_; ++k) {
      if (atol_[k] < 0) continue;
      const double r = value(k) / (atol_[k] + rtol_ * std::abs(y_[k]));
      sum += r * r;
      ++counted;
    }
    return counted > 0 ? std::sqrt(sum / counted) : 0.0;
  };
  const double* f0 = stage(0);
  const double d0 = norm([&](int k) { return y_[k]; });
  const double d1 = norm([&](int k) { return f0[k]; });
  // too small to estimate from (Hairer's thresholds): a tiny first step, the controller grows it
  double h0 = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * d0 / d1;
  h0 = std::min(h0, h_max);
  for (int k = 0; k < dim_; ++k) tmp_[k] = y_[k] + h0 * f0[k];
  double* f_trial = stage(1);  // scratch: stage 1 is rewritten by the next attempt()
  rhs_.eval(tmp_.data(), f_trial);
  ++evals_;
  const double d2 = norm([&](int k) { return f_trial[k] - f0[k]; }) / h0;
  const double dm = std::max(d1, d2);
  const double h1 = dm <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dm, 1.0 / tab_.order);
  return std::min({100.0 * h0, h1, h_max});
}

const double* RkStepper::f1() const {
  return stage(tab_.stages - 1);
}

void RkStepper::ensureStages() {
  if (extra_stages_) return;
  for (int j = tab_.stages; j < tab_.dense_stages; ++j) {
    combine(a_rows_[j], h_, tmp_.data());
    rhs_.eval(tmp_.data(), stage(j));
    ++evals_;
  }
  extra_stages_ = true;
}

// The interpolant's stage weights at th: h b_j(th) = h sum_q p_jq th^(q+1), and their time
// derivatives b_j'(th) = sum_q (q + 1) p_jq th^q. A value is then y0 + sum_j w_j k_j, computed in
// the same order for one component as for the whole state, so that a witness evaluated on one
// component agrees to the last bit with the state the event starts from.
namespace {

// w_r = scale * sum_q p_rq th^(q+1) (value) or sum_q (q + 1) p_rq th^q (rate), by Horner's rule
// with the degree and the (padded) row count known at compile time. The rows are the inner loop
// (the coefficients stored degree-major, pt[q * R + r], zero-padded to R rows, and for the rate
// pre-multiplied by q + 1), so that the compiler vectorizes across rows; each row's arithmetic
// is the same sequence of operations as a row-wise Horner, so the weights are the same to the
// last bit.
template <int D, int R>
void hornerRows(const double* __restrict pt, int rows, double th, double scale, bool rate,
                double* __restrict w) {
  double acc[R];
  for (int r = 0; r < R; ++r) acc[r] = pt[(D - 1) * R + r];
  for (int q = D - 2; q >= 0; --q)
    for (int r = 0; r < R; ++r) acc[r] = acc[r] * th + pt[q * R + r];
  if (!rate)
    for (int r = 0; r < R; ++r) acc[r] *= scale;
  for (int r = 0; r < R; ++r) w[r] = acc[r];  // all R: a fixed-size store, not a memcpy call
}

}  // namespace

void RkStepper::stageWeights(double th, bool rate) {
  ensureStages();
  // the same weights again (a witness and the state at one window end, several witnesses at
  // one th): the step's stages have not changed since (attempt() and restart() reset this)
  if (th == w_th_ && rate == w_rate_) return;
  w_th_ = th;
  w_rate_ = rate;
  const int rows = static_cast<int>(dense_stage_.size());
  const double scale = h_ * th;
  const double* p = rate ? dense_rate_pt_.data() : dense_pt_.data();
  double* w = w_.data();
  if (padded_rows_ == kPadRowsSmall && tab_.dense_degree == 4)
    return hornerRows<4, kPadRowsSmall>(p, rows, th, scale, rate, w);
  if (padded_rows_ == kPadRows) {
    switch (tab_.dense_degree) {
      case 6:
        return hornerRows<6, kPadRows>(p, rows, th, scale, rate, w);
      case 7:
        return hornerRows<7, kPadRows>(p, rows, th, scale, rate, w);
    }
  }
  const int deg = tab_.dense_degree, stride = padded_rows_;
  for (int r = 0; r < rows; ++r) {
    double acc = p[static_cast<size_t>(deg - 1) * stride + r];
    for (int q = deg - 2; q >= 0; --q) acc = acc * th + p[static_cast<size_t>(q) * stride + r];
    w[r] = rate ? acc : scale * acc;
  }
}

double RkStepper::component(int k, double th) {
  if (th == 0.0) return y_[k];
  if (th == 1.0) return y1_[k];
  stageWeights(th, false);
  double acc = y_[k];
  for (size_t r = 0; r < dense_stage_.size(); ++r) acc += w_[r] * stage(dense_stage_[r])[k];
  return acc;
}

double RkStepper::componentRate(int k, double th) {
  stageWeights(th, true);
  double acc = 0.0;
  for (size_t r = 0; r < dense_stage_.size(); ++r) acc += w_[r] * stage(dense_stage_[r])[k];
  return acc;
}

void RkStepper::interpolate(double th, double* __restrict out) {
  interpolateRange(th, 0, dim_, out);
}

void RkStepper::interpolateRange(double th, int first, int count, double* __restrict out) {
  const double* __restrict y = y_.data() + first;
  double* __restrict o = out + first;
  if (th == 0.0) {
    std::copy(y, y + count, o);
    return;
  }
  if (th == 1.0) {
    std::copy(y1_.data() + first, y1_.data() + first + count, o);
    return;
  }
  stageWeights(th, false);
  for (int k = 0; k < count; ++k) o[k] = y[k];
  for (size_t r = 0; r < dense_stage_.size(); ++r) {
    const double w = w_[r];
    const double* __restrict kj = stage(dense_stage_[r]) + first;
    for (int k = 0; k < count; ++k) o[k] += w * kj[k];
  }
}

}  // namespace metrosync::ode
