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
#pragma once

#include <vector>

#include "sim/ode/rk_tableau.h"

namespace metrosync::ode {

struct OdeRhs {
  virtual ~OdeRhs() = default;
  virtual void eval(const double* y, double* dy) = 0;
};

class RkStepper {
 public:
  RkStepper(const RkTableau& tableau, int dim, OdeRhs& rhs);

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

  // The step size to try next after an attempt with error norm `err` (Hairer's PI control).
  double nextStepSize(double h, double err, bool accepted);
  // A first step size for the current point (Hairer's starting-step heuristic, "Solving ODEs I"
  // II.4; hinit in DOPRI5), at most h_max: costs one f evaluation.
  double initialStepSize(double h_max);

  // the current point, and the attempted step (valid after attempt())
  double t() const { return t_; }
  const double* y() const { return y_.data(); }
  const double* f() const { return k_.data(); }  // f(y) at the current point
  double h() const { return h_; }
  double t1() const { return t_ + h_; }
  const double* y1() const { return y1_.data(); }
  const double* f1() const;  // f(y1) (FSAL stage; evaluated on demand otherwise)

  // Dense output at t0 + th h, th in [0, 1]: the whole state, one component, or the time
  // derivative of one component's interpolant.
  void interpolate(double th, double* __restrict out);
  // components [first, first + count) only, into out[first ...] (the same bits as interpolate)
  void interpolateRange(double th, int first, int count, double* __restrict out);
  double component(int k, double th);
  double componentRate(int k, double th);

  int dim() const { return dim_; }
  const RkTableau& tableau() const { return tab_; }
  long evaluations() const { return evals_; }

 private:
  void ensureStages();                      // the interpolant's extra stages
  void stageWeights(double th, bool rate);  // w_ at th

  // y0 + h sum_l w_l k_l over the nonzero weights (l, w_l)
  using Weights = std::vector<std::pair<int, double>>;
  void combine(const Weights& w, double h, double* __restrict out) const;
  double* stage(int j) { return &k_[static_cast<size_t>(j) * dim_]; }
  const double* stage(int j) const { return &k_[static_cast<size_t>(j) * dim_]; }

  const RkTableau& tab_;
  int dim_;
  OdeRhs& rhs_;
  double rtol_ = 1e-8;
  Norm norm_ = Norm::Max;
  std::vector<double> atol_;
  std::vector<Weights> a_rows_;   // (dense_stages): nonzero a_jl of each stage
  Weights b_, e_;                 // nonzero b_l, e_l
  std::vector<int> dense_stage_;  // stages with a nonzero row of p, (rows)
  std::vector<double> dense_p_;   // their rows of p, (rows x degree)
  // p and (q + 1) p, (degree x padded_rows_): rows padded with zeros to a fixed count, so that
  // the interpolant's weights are one fixed-size vector loop per degree
  static constexpr int kPadRowsSmall = 8, kPadRows = 16;  // dopri5: 7 stages; Verner's: 12, 16
  int padded_rows_ = kPadRows;
  std::vector<double> dense_pt_, dense_rate_pt_;
  double t_ = 0.0, h_ = 0.0;
  std::vector<double> y_, y1_, tmp_;
  std::vector<double> k_;  // (dense_stages x dim), stage-major; k_0 = f(y)
  bool extra_stages_ = false;
  std::vector<double> w_;  // (padded rows): the interpolant's stage weights
  double w_th_ = -1.0;     // the th and kind w_ holds (th < 0: none)
  bool w_rate_ = false;
  double err_old_ = 1e-4;
  long evals_ = 0;
};

}  // namespace metrosync::ode

namespace metrosync::direct {  // the direct engine's names from before the toolkit was shared
using ode::OdeRhs;
using ode::RkStepper;
}  // namespace metrosync::direct
