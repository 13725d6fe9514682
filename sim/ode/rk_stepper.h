// A generic embedded Runge-Kutta stepper with error control and dense output (Hairer, Norsett,
// Wanner, "Solving ODEs I", II.4 and II.6). It knows nothing about metronomes: it advances
// dy/dt = f(y) (autonomous) with any RkTableau, one step at a time, and the caller decides what
// to do with each step (keep it whole, cut it at an event, or redo it smaller).
//
//   attempt(h)   one step from (t, y): y1 and the error norm (<= 1: acceptable)
//   interpolate  anywhere inside the attempted step, from its continuous extension
//   advance()    move to the end of the step (the FSAL stage becomes the next k_0)
//   restart(y)   move anywhere else (after an event): costs one f evaluation
// Used by the direct engine (sim/engines/direct) and the slow flow (sim/engines/slow_flow).
//
// One class template, two knobs known to the compiler where the caller knows them:
//   Rhs  the right-hand side, anything with eval(const double* y, double* dy); OdeRhs (virtual)
//        for callers that choose it at run time, a final class for the engine's hot loop, so
//        that every stage's evaluation is inlined;
//   Dim  the state's size, or kDynamic: a fixed size makes every loop over the components one of
//        known length (unrolled and vectorized) and every buffer part of the object;
//   Quad the number of trailing components that are pure quadratures (f never reads them: the
//        direct engine's energy ledger): the intermediate stages' states leave them out, the
//        step's end and the dense output include them.
// The arithmetic is the same, operation for operation and in the same order, for every choice of
// the two: a fixed-size stepper's steps and states equal the dynamic one's bit for bit.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sim/ode/rk_tableau.h"

namespace metrosync::ode {

struct OdeRhs {
  virtual ~OdeRhs() = default;
  virtual void eval(const double* y, double* dy) = 0;
};

inline constexpr int kDynamic = -1;

namespace detail {

// The most stages of any tableau (verner76 with its interpolant: 16), and the most nonzero
// weights of any of its rows (verner76: 15).
constexpr int kMaxStages = 16;
constexpr int kMaxTerms = 16;

// `count` doubles, in the object (fixed size) or on the heap (kDynamic).
template <int Size>
struct Buffer {
  explicit Buffer(int) {}
  double* data() { return v.data(); }
  const double* data() const { return v.data(); }
  std::array<double, Size> v{};
};
template <>
struct Buffer<kDynamic> {
  explicit Buffer(int count) : v(static_cast<size_t>(count), 0.0) {}
  double* data() { return v.data(); }
  const double* data() const { return v.data(); }
  std::vector<double> v;
};

// Nonzero weights (l, w_l) of one row, in stage order.
struct Row {
  int count = 0;
  std::array<int, kMaxTerms> stage{};
  std::array<double, kMaxTerms> weight{};
};
Row nonzeroRow(const std::vector<double>& w, int count);

// out = y + sum_t hw_t ks_t, the terms added in stage order (the same sum, to the last bit, as a
// stage-by-stage accumulation); the component loop has a known length when Dim is fixed.
template <int Dim, int T>
void combineTerms(const double* __restrict y, const double* const* ks, const double* hw, int dim,
                  double* __restrict out) {
  const int n = Dim > 0 ? Dim : dim;
  for (int k = 0; k < n; ++k) {
    double acc = y[k];
    for (int t = 0; t < T; ++t) acc += hw[t] * ks[t][k];
    out[k] = acc;
  }
}

using CombineFn = void (*)(const double*, const double* const*, const double*, int, double*);

template <int Dim, int... T>
constexpr std::array<CombineFn, sizeof...(T)> combineTable(std::integer_sequence<int, T...>) {
  return {&combineTerms<Dim, T>...};
}

template <int Dim>
constexpr auto kCombine = combineTable<Dim>(std::make_integer_sequence<int, kMaxTerms + 1>{});

// The interpolant's coefficients, degree-major and zero-padded to a fixed row count: p_rq and
// (q + 1) p_rq, so that a weight evaluation is one fixed-size vector loop per degree.
struct DenseTable {
  static constexpr int kPadRowsSmall = 8, kPadRows = 16;  // dopri5: 7 stages; Verner's: 12, 16
  static constexpr int kMaxDegree = 8;                    // dopri5: 4; verner65: 6; verner76: 7
  explicit DenseTable(const RkTableau& tab);
  std::vector<int> stage;  // stages with a nonzero row of p, (rows)
  int padded_rows = kPadRows;
  int degree = 0;
  std::vector<double> pt, rate_pt;  // (kMaxDegree x padded_rows), zero past the degree
  // w_r at th (value: h b_r(th); rate: b_r'(th)), into w (padded_rows)
  void weights(double th, double h, bool rate, double* w) const;
};

// Hairer's DOPRI5 controller: the next step after an attempt with error norm err; log2_err_old
// holds log2 of the last accepted step's error (at least kLog2ErrFloor: 1e-4, Hairer's floor).
constexpr double kLog2ErrFloor = -13.287712379549449;  // log2(1e-4)
double nextStepSize(const RkTableau& tab, double& log2_err_old, double h, double err,
                    bool accepted);

}  // namespace detail

template <class Rhs, int Dim = kDynamic, int Quad = 0>
class RkStepperT {
 public:
  RkStepperT(const RkTableau& tableau, int dim, Rhs& rhs);

  // Local error target per component: |err_k| <= atol_k + rtol * max(|y0_k|, |y1_k|); components
  // with atol_k < 0 are not controlled (quadratures that nothing depends on).
  void setTolerances(double rtol, std::vector<double> atol);
  // How the components' scaled errors combine into the error norm: the worst one (the default:
  // every component is held to its target; the direct engine) or their root mean square (Hairer's
  // DOPRI5 norm: the slow flow, whose 2N components are the Re/Im parts of N amplitudes).
  enum class Norm { Max, Rms };
  void setNorm(Norm norm) { norm_ = norm; }

  void restart(double t, const double* y);
  // One step of size h from the current point; returns the error norm (see setNorm).
  double attempt(double h);
  // Moves to the end of the attempted step.
  void advance();
  // Makes this stepper hold a step another stepper of the same tableau and right-hand side took
  // (its t, h, y, y1 and its first tableau().stages stages, stagesData()): its dense output is
  // then that step's to the bit (a recorder interpolating a run's steps on another thread).
  void load(double t, double h, const double* y, const double* y1, const double* stages);
  // The attempted step's stages k_0 .. k_{stages-1}, stage-major (stages x dim)
  const double* stagesData() const { return k_.data(); }

  // The step size to try next after an attempt with error norm `err` (Hairer's PI control).
  double nextStepSize(double h, double err, bool accepted) {
    return detail::nextStepSize(tab_, log2_err_old_, h, err, accepted);
  }
  // A first step size for the current point (Hairer's starting-step heuristic, "Solving ODEs I"
  // II.4; hinit in DOPRI5), at most h_max: costs one f evaluation.
  double initialStepSize(double h_max);

  // the current point, and the attempted step (valid after attempt())
  double t() const { return t_; }
  const double* y() const { return y_.data(); }
  const double* f() const { return stage(0); }  // f(y) at the current point
  double h() const { return h_; }
  double t1() const { return t_ + h_; }
  const double* y1() const { return y1_.data(); }
  const double* f1() const { return stage(tab_.stages - 1); }  // f(y1) (the FSAL stage)

  // Dense output at t0 + th h, th in [0, 1]: the whole state, one component, or the time
  // derivative of one component's interpolant.
  void interpolate(double th, double* __restrict out) { interpolateRange(th, 0, dim(), out); }
  // components [first, first + count) only, into out[first ...] (the same bits as interpolate)
  void interpolateRange(double th, int first, int count, double* __restrict out);
  // The interpolant's stage weights at th for a step of size h (DenseTable::kPadRows values: what
  // interpolateRange computes for its th), and the interpolant from weights given so: a caller
  // that interpolates many steps at the same fractions computes their weights once (h = 1) and
  // scales them by each step's h.
  void denseWeights(double th, double h, double* w) const { dense_.weights(th, h, false, w); }
  void interpolateWith(const double* w, int first, int count, double* __restrict out);
  // The interpolant at Q points at once from their weights, by stage row (w[r][q]: what
  // denseWeights gives for point q, its r-th value): components [first, first + count) of point q
  // into out[q * count ...]. The same sums as interpolateWith, point by point, in the same order.
  // C: count, when the compiler may know it (the sums then stay in registers), else kDynamic.
  template <int Q, int C = kDynamic>
  void interpolateMany(const double (&w)[detail::DenseTable::kPadRows][Q], int first, int count,
                       double* __restrict out);
  double component(int k, double th);
  double componentRate(int k, double th);

  // One component's interpolant over the attempted step as a polynomial in th,
  //   y_k(th) = y0_k + th (a_0 + th (a_1 + ... + th a_{d-1})),
  // for root finding at a fraction of the cost of component(): within a few ulps of it, not the
  // same bits (confirm a root on component()). Fills a (dense degree d values), returns d.
  struct Polynomial {
    double y0 = 0.0;
    int degree = 0;
    std::array<double, detail::DenseTable::kMaxDegree> a{};
    double operator()(double th) const {
      double acc = a[degree - 1];
      for (int q = degree - 2; q >= 0; --q) acc = acc * th + a[q];
      return y0 + th * acc;
    }
    // the value and its derivative in th, by one Horner pass each
    std::pair<double, double> valueRate(double th) const {
      double acc = a[degree - 1], rate = degree * a[degree - 1];
      for (int q = degree - 2; q >= 0; --q) {
        acc = acc * th + a[q];
        rate = rate * th + (q + 1) * a[q];
      }
      return {y0 + th * acc, rate};
    }
  };
  Polynomial componentPolynomial(int k);

  int dim() const { return Dim > 0 ? Dim : dim_; }
  const RkTableau& tableau() const { return tab_; }
  long evaluations() const { return evals_; }

 private:
  void ensureStages();                      // the interpolant's extra stages
  void stageWeights(double th, bool rate);  // w_ at th

  // y0 + h sum_l w_l k_l over the row's nonzero weights: the components that f reads (a stage's
  // state), or every component (the step's end)
  enum class Span { Stage, Whole };
  template <Span S>
  void combine(const detail::Row& w, double h, double* __restrict out) const;
  double* stage(int j) { return k_.data() + static_cast<size_t>(j) * dim(); }
  const double* stage(int j) const { return k_.data() + static_cast<size_t>(j) * dim(); }
  void eval(const double* y, double* dy) {
    rhs_.eval(y, dy);
    ++evals_;
  }

  static constexpr int kStageDoubles = Dim > 0 ? Dim* detail::kMaxStages : kDynamic;

  const RkTableau& tab_;
  int dim_;
  Rhs& rhs_;
  double rtol_ = 1e-8;
  Norm norm_ = Norm::Max;
  std::vector<double> atol_;
  std::array<detail::Row, detail::kMaxStages> a_rows_;  // nonzero a_jl of each stage
  detail::Row b_, e_;                                   // nonzero b_l, e_l
  detail::DenseTable dense_;
  double t_ = 0.0, h_ = 0.0;
  detail::Buffer<Dim> y_, y1_, tmp_;
  detail::Buffer<kStageDoubles> k_;  // (dense_stages x dim), stage-major; k_0 = f(y)
  bool extra_stages_ = false;
  std::array<double, detail::DenseTable::kPadRows> w_{};  // the interpolant's stage weights
  double w_th_ = -1.0;                                    // the th and kind w_ holds (th < 0: none)
  bool w_rate_ = false;
  double log2_err_old_ = detail::kLog2ErrFloor;
  long evals_ = 0;
};

// The stepper of callers that choose their right-hand side at run time (the slow flow, the
// continuation's limit cycles, the tests).
using RkStepper = RkStepperT<OdeRhs, kDynamic, 0>;

// --- implementation ---------------------------------------------------------------------------

template <class Rhs, int Dim, int Quad>
RkStepperT<Rhs, Dim, Quad>::RkStepperT(const RkTableau& tableau, int dim, Rhs& rhs)
    : tab_(tableau),
      dim_(dim),
      rhs_(rhs),
      atol_(dim, 0.0),
      dense_(tableau),
      y_(dim),
      y1_(dim),
      tmp_(dim),
      k_(tableau.dense_stages * dim) {
  if (!tab_.fsal) throw std::invalid_argument("RkStepper: the method must be FSAL");
  if (Dim > 0 && dim != Dim) throw std::invalid_argument("RkStepper: dim differs from Dim");
  if (tab_.dense_stages > detail::kMaxStages)
    throw std::invalid_argument("RkStepper: too many stages");
  for (int j = 0; j < tab_.dense_stages; ++j) a_rows_[j] = detail::nonzeroRow(tab_.a[j], j);
  b_ = detail::nonzeroRow(tab_.b, tab_.stages);
  e_ = detail::nonzeroRow(tab_.e, tab_.stages);
}

template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::setTolerances(double rtol, std::vector<double> atol) {
  rtol_ = rtol;
  atol_ = std::move(atol);
}

template <class Rhs, int Dim, int Quad>
template <typename RkStepperT<Rhs, Dim, Quad>::Span S>
void RkStepperT<Rhs, Dim, Quad>::combine(const detail::Row& w, double h,
                                         double* __restrict out) const {
  if constexpr (Dim > 0) {
    // the running sums in registers, terms added in stage order (the same bits as below)
    constexpr int n = S == Span::Stage ? Dim - Quad : Dim;
    double acc[n];
    const double* __restrict y = y_.data();
    for (int k = 0; k < n; ++k) acc[k] = y[k];
    for (int t = 0; t < w.count; ++t) {
      const double hw = h * w.weight[t];
      const double* __restrict ks = stage(w.stage[t]);
      for (int k = 0; k < n; ++k) acc[k] += hw * ks[k];
    }
    for (int k = 0; k < n; ++k) out[k] = acc[k];
  } else {
    const double* ks[detail::kMaxTerms];
    double hw[detail::kMaxTerms];
    for (int t = 0; t < w.count; ++t) {
      ks[t] = stage(w.stage[t]);
      hw[t] = h * w.weight[t];
    }
    const int n = S == Span::Stage ? dim_ - Quad : dim_;
    detail::kCombine<Dim>[w.count](y_.data(), ks, hw, n, out);
  }
}

template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::restart(double t, const double* y) {
  w_th_ = -1.0;
  t_ = t;
  h_ = 0.0;
  std::copy(y, y + dim(), y_.data());
  eval(y_.data(), stage(0));
}

template <class Rhs, int Dim, int Quad>
double RkStepperT<Rhs, Dim, Quad>::attempt(double h) {
  w_th_ = -1.0;
  h_ = h;
  extra_stages_ = false;
  const int s = tab_.stages, n = dim();
  // stages 1 .. s-2; s-1 is the FSAL stage, f(y1)
  for (int j = 1; j < s - 1; ++j) {
    combine<Span::Stage>(a_rows_[j], h, tmp_.data());
    eval(tmp_.data(), stage(j));
  }
  combine<Span::Whole>(b_, h, y1_.data());
  eval(y1_.data(), stage(s - 1));
  // the embedded difference sum_l e_l k_l, stage by stage (vectorized over the components; per
  // component the same sums in the same order as one component at a time)
  double* __restrict diff = tmp_.data();
  for (int k = 0; k < n; ++k) diff[k] = 0.0;
  for (int t = 0; t < e_.count; ++t) {
    const double el = e_.weight[t];
    const double* __restrict kl = stage(e_.stage[t]);
    for (int k = 0; k < n; ++k) diff[k] += el * kl[k];
  }
  // error norm: the worst component relative to its tolerance, or the root mean square
  double err = 0.0, sum = 0.0;
  int counted = 0;
  const double* y0 = y_.data();
  const double* y1 = y1_.data();
  for (int k = 0; k < n; ++k) {
    if (atol_[k] < 0) continue;
    const double sc = atol_[k] + rtol_ * std::max(std::abs(y0[k]), std::abs(y1[k]));
    const double r = std::abs(h * diff[k]) / sc;
    if (!(r <= err)) err = r;  // a NaN wins: a step that produced one is never accepted
    sum += r * r;
    ++counted;
  }
  if (norm_ == Norm::Rms && std::isfinite(err)) err = counted > 0 ? std::sqrt(sum / counted) : 0.0;
  if (!std::isfinite(err)) err = std::numeric_limits<double>::infinity();
  return err;
}

template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::advance() {
  w_th_ = -1.0;
  t_ += h_;
  std::swap(y_, y1_);
  const double* fsal = stage(tab_.stages - 1);
  std::copy(fsal, fsal + dim(), stage(0));
  h_ = 0.0;
}

template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::load(double t, double h, const double* y, const double* y1,
                                      const double* stages) {
  w_th_ = -1.0;
  extra_stages_ = false;
  t_ = t;
  h_ = h;
  std::copy(y, y + dim(), y_.data());
  std::copy(y1, y1 + dim(), y1_.data());
  std::copy(stages, stages + static_cast<size_t>(tab_.stages) * dim(), k_.data());
}

template <class Rhs, int Dim, int Quad>
double RkStepperT<Rhs, Dim, Quad>::initialStepSize(double h_max) {
  // d0 = ||y0||, d1 = ||f(y0)||, d2 = ||f'|| estimated by a trial Euler step; RMS norms in the
  // units of the error target
  const int n = dim();
  const double* y = y_.data();
  auto norm = [&](auto&& value) {
    double sum = 0.0;
    int counted = 0;
    for (int k = 0; k < n; ++k) {
      if (atol_[k] < 0) continue;
      const double r = value(k) / (atol_[k] + rtol_ * std::abs(y[k]));
      sum += r * r;
      ++counted;
    }
    return counted > 0 ? std::sqrt(sum / counted) : 0.0;
  };
  const double* f0 = stage(0);
  const double d0 = norm([&](int k) { return y[k]; });
  const double d1 = norm([&](int k) { return f0[k]; });
  // too small to estimate from (Hairer's thresholds): a tiny first step, the controller grows it
  double h0 = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * d0 / d1;
  h0 = std::min(h0, h_max);
  double* trial = tmp_.data();
  for (int k = 0; k < n; ++k) trial[k] = y[k] + h0 * f0[k];
  double* f_trial = stage(1);  // scratch: stage 1 is rewritten by the next attempt()
  eval(trial, f_trial);
  const double d2 = norm([&](int k) { return f_trial[k] - f0[k]; }) / h0;
  const double dm = std::max(d1, d2);
  const double h1 = dm <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dm, 1.0 / tab_.order);
  return std::min({100.0 * h0, h1, h_max});
}

template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::ensureStages() {
  if (extra_stages_) return;
  for (int j = tab_.stages; j < tab_.dense_stages; ++j) {
    combine<Span::Stage>(a_rows_[j], h_, tmp_.data());
    eval(tmp_.data(), stage(j));
  }
  extra_stages_ = true;
}

// The interpolant's stage weights at th: h b_j(th) = h sum_q p_jq th^(q+1), and their time
// derivatives b_j'(th) = sum_q (q + 1) p_jq th^q. A value is then y0 + sum_j w_j k_j, computed in
// the same order for one component as for the whole state, so that a witness evaluated on one
// component agrees to the last bit with the state the event starts from.
template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::stageWeights(double th, bool rate) {
  ensureStages();
  // the same weights again (a witness and the state at one window end, several witnesses at
  // one th): the step's stages have not changed since (attempt() and restart() reset this)
  if (th == w_th_ && rate == w_rate_) return;
  w_th_ = th;
  w_rate_ = rate;
  dense_.weights(th, h_, rate, w_.data());
}

template <class Rhs, int Dim, int Quad>
double RkStepperT<Rhs, Dim, Quad>::component(int k, double th) {
  if (th == 0.0) return y_.data()[k];
  if (th == 1.0) return y1_.data()[k];
  stageWeights(th, false);
  double acc = y_.data()[k];
  const int rows = static_cast<int>(dense_.stage.size());
  for (int r = 0; r < rows; ++r) acc += w_[r] * stage(dense_.stage[r])[k];
  return acc;
}

template <class Rhs, int Dim, int Quad>
typename RkStepperT<Rhs, Dim, Quad>::Polynomial RkStepperT<Rhs, Dim, Quad>::componentPolynomial(
    int k) {
  ensureStages();
  Polynomial p;
  p.y0 = y_.data()[k];
  p.degree = dense_.degree;
  const int rows = static_cast<int>(dense_.stage.size()), pad = dense_.padded_rows;
  // row by row, each coefficient's sum in row order (the coefficients are independent: one vector
  // loop over them per row)
  constexpr int kDeg = detail::DenseTable::kMaxDegree;
  std::array<double, kDeg> acc{};
  for (int r = 0; r < rows; ++r) {
    const double kr = stage(dense_.stage[r])[k];
    for (int q = 0; q < kDeg; ++q) acc[q] += dense_.pt[q * pad + r] * kr;
  }
  for (int q = 0; q < p.degree; ++q) p.a[q] = h_ * acc[q];
  return p;
}

template <class Rhs, int Dim, int Quad>
double RkStepperT<Rhs, Dim, Quad>::componentRate(int k, double th) {
  stageWeights(th, true);
  double acc = 0.0;
  const int rows = static_cast<int>(dense_.stage.size());
  for (int r = 0; r < rows; ++r) acc += w_[r] * stage(dense_.stage[r])[k];
  return acc;
}

template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::interpolateRange(double th, int first, int count,
                                                  double* __restrict out) {
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
  interpolateWith(w_.data(), first, count, out);
}

template <class Rhs, int Dim, int Quad>
void RkStepperT<Rhs, Dim, Quad>::interpolateWith(const double* w, int first, int count,
                                                 double* __restrict out) {
  ensureStages();
  const double* __restrict y = y_.data() + first;
  double* __restrict o = out + first;
  for (int k = 0; k < count; ++k) o[k] = y[k];
  const int rows = static_cast<int>(dense_.stage.size());
  for (int r = 0; r < rows; ++r) {
    const double wr = w[r];
    const double* __restrict kj = stage(dense_.stage[r]) + first;
    for (int k = 0; k < count; ++k) o[k] += wr * kj[k];
  }
}

template <class Rhs, int Dim, int Quad>
template <int Q, int C>
void RkStepperT<Rhs, Dim, Quad>::interpolateMany(const double (&w)[detail::DenseTable::kPadRows][Q],
                                                 int first, int count, double* __restrict out) {
  ensureStages();
  const int rows = static_cast<int>(dense_.stage.size());
  const double* y = y_.data() + first;
  if constexpr (C > 0) {
    // every component's Q sums side by side (acc[k]: one vector of Q lanes), a stage's row and
    // its weights read once for them all
    double acc[C][Q];
    for (int k = 0; k < C; ++k)
      for (int q = 0; q < Q; ++q) acc[k][q] = y[k];
    for (int r = 0; r < rows; ++r) {
      const double* __restrict kr = stage(dense_.stage[r]) + first;
      for (int k = 0; k < C; ++k)
        for (int q = 0; q < Q; ++q) acc[k][q] += w[r][q] * kr[k];
    }
    for (int k = 0; k < C; ++k)
      for (int q = 0; q < Q; ++q) out[q * C + k] = acc[k][q];
  } else {
    for (int k = 0; k < count; ++k) {
      double acc[Q];  // the Q points' sums for one component, side by side
      for (int q = 0; q < Q; ++q) acc[q] = y[k];
      for (int r = 0; r < rows; ++r) {
        const double kv = stage(dense_.stage[r])[first + k];
        for (int q = 0; q < Q; ++q) acc[q] += w[r][q] * kv;
      }
      for (int q = 0; q < Q; ++q) out[q * count + k] = acc[q];
    }
  }
}

extern template class RkStepperT<OdeRhs, kDynamic, 0>;

}  // namespace metrosync::ode

namespace metrosync::direct {  // the direct engine's names from before the toolkit was shared
using ode::OdeRhs;
using ode::RkStepper;
}  // namespace metrosync::direct
