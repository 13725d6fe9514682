// The Ceres plugin's body (sim/analysis/fit/ceres_plugin.h): solveLocal's least squares
// (sim/analysis/fit/least_squares.h) by Ceres Solver.
#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <stdexcept>

#include "sim/analysis/fit/ceres_plugin.h"
#include "sim/analysis/fit/difference_step.h"

namespace metrosync {

namespace {

// The solver stops when the cost changes by less than this fraction in a step.
constexpr double kFunctionTolerance = 1e-10;
// The first trust region: Levenberg-Marquardt's damping 1 / kInitialRadius of the Jacobian's
// scaled diagonal, far below its smallest eigenvalue on the fit's records (five keys correlated
// to 0.999..., their principal variances spread over 1e8): Gauss-Newton's steps from the first
// iteration, which the exact derivatives make reliable; a step that fails shrinks the region as
// ever. (Ceres' default, 1e4, damped the weakest direction to a crawl: 7 iterations back from 4
// standard deviations, where 2 do.)
constexpr double kInitialRadius = 1e8;
// The model is run this far (in units of the scale) inside a lower bound: a rig may not exist at
// the bound itself (a decay rate of 0 leaves no impulse for a steady amplitude), and this is far
// below anything the data resolve.
constexpr double kInsideBound = 1e-9;

// Ceres' functor: one parameter block of size 1 per fitted parameter (so that any can be held).
// A central difference at a bound reaches past it, where the model may not exist (a negative
// friction coefficient): the value is held just inside the bound there, a one-sided difference.
struct Functor {
  const LocalProblem* p;
  std::vector<int> block_of;  // parameter j -> its block, -1 when held
  std::vector<double> valuesAt(double const* const* blocks) const {
    std::vector<double> v = p->start;
    for (std::size_t j = 0; j < v.size(); ++j)
      if (block_of[j] >= 0)
        v[j] = std::max(blocks[block_of[j]][0] * p->scale[j],
                        p->lower[j] + kInsideBound * p->scale[j]);
    return v;
  }
  bool operator()(double const* const* blocks, double* r) const {
    try {
      if (!p->residuals(valuesAt(blocks), r)) return false;
    } catch (const std::exception&) {
      return false;
    }
    return finite(r, p->residual_count);
  }
  // the residuals and the problem's own derivatives d r / d (value / scale) into each block's
  // jacobian (one column each)
  bool withJacobian(double const* const* blocks, double* r, double** jac) const {
    const int m = p->residual_count;
    std::vector<double> J(static_cast<std::size_t>(m) * p->start.size());
    try {
      if (!p->jacobian(valuesAt(blocks), r, J.data())) return false;
    } catch (const std::exception&) {
      return false;
    }
    if (!finite(r, m) || !finite(J.data(), static_cast<int>(J.size()))) return false;
    for (std::size_t j = 0; j < block_of.size(); ++j) {
      if (block_of[j] < 0 || jac[block_of[j]] == nullptr) continue;
      for (int i = 0; i < m; ++i) jac[block_of[j]][i] = J[j * m + i] * p->scale[j];
    }
    return true;
  }
  static bool finite(const double* x, int count) {
    for (int i = 0; i < count; ++i)
      if (!std::isfinite(x[i])) return false;
    return true;
  }
};

// The residuals and their derivatives: the problem's own where it gives them, else central
// differences (one-sided where the model fails on one side) over each key's own step
// (difference_step.h): Ceres' numeric differences take one relative step for every key, too long
// for a key the record determines to 1e-5 of itself. A shrunk step is kept for the next evaluation
// (and doubled back towards the first while it moves the residuals by less than a quarter of
// kStepRise).
class ModelCost : public ceres::DynamicCostFunction {
 public:
  explicit ModelCost(Functor f) : f_(std::move(f)) {}
  void addKey() {
    AddParameterBlock(1);
    shrink_.push_back(1.0);
  }
  bool Evaluate(double const* const* x, double* r, double** jac) const override {
    if (jac != nullptr && f_.p->jacobian) return f_.withJacobian(x, r, jac);
    if (!f_(x, r)) return false;
    if (jac == nullptr) return true;
    const int m = num_residuals();
    double sigma2 = 0.0;
    for (int i = 0; i < m; ++i) sigma2 += r[i] * r[i] / m;
    for (std::size_t b = 0; b < shrink_.size(); ++b)
      if (jac[b] != nullptr && !column(x, r, sigma2, b, jac[b])) return false;
    return true;
  }

 private:
  // d r / d x_b into col; false when the model fails on both sides
  bool column(double const* const* x, const double* r0, double sigma2, std::size_t b,
              double* col) const {
    const int m = num_residuals();
    const double h0 = firstDifferenceStep(x[b][0]);
    std::vector<double> plus(m), minus(m), moved(shrink_.size());
    std::vector<const double*> at(shrink_.size());
    for (std::size_t c = 0; c < at.size(); ++c) moved[c] = x[c][0], at[c] = &moved[c];
    for (double h = shrink_[b] * h0;;) {
      moved[b] = x[b][0] + h;
      const bool p = f_(at.data(), plus.data());
      moved[b] = x[b][0] - h;
      const bool q = f_(at.data(), minus.data());
      if (!p && !q) return false;
      const double* hi = p ? plus.data() : r0;
      const double* lo = q ? minus.data() : r0;
      const double span = (p ? h : 0.0) + (q ? h : 0.0);
      double rise = 0.0;
      for (int i = 0; i < m; ++i) {
        col[i] = (hi[i] - lo[i]) / span;
        rise += col[i] * h * col[i] * h;
      }
      rise = sigma2 > 0 ? rise / sigma2 : 0.0;
      const double next = shrunkDifferenceStep(h, h0, rise);
      if (next == 0.0) {
        shrink_[b] = rise < kStepRise / 4 ? std::min(1.0, 2 * h / h0) : h / h0;
        return true;
      }
      h = next;
    }
  }
  Functor f_;
  mutable std::vector<double> shrink_;  // per key: its step over its first step
};

// Keeps the last accepted point: when a later step's derivatives cannot be evaluated (the solve
// ends in FAILURE), Ceres leaves the user's values at the start.
struct LastAccepted : ceres::IterationCallback {
  const std::vector<double>* x;
  std::vector<double> kept;
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (s.step_is_successful || s.iteration == 0) kept = *x;
    return ceres::SOLVER_CONTINUE;
  }
};

// The Levenberg-Marquardt options: quiet, the state seen by the callback after every iteration.
ceres::Solver::Options solverOptions(const LocalProblem& p, LastAccepted* last) {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = p.max_iterations;
  o.function_tolerance = kFunctionTolerance;
  o.logging_type = ceres::SILENT;
  o.update_state_every_iteration = true;
  o.callbacks.push_back(last);
  o.initial_trust_region_radius = kInitialRadius;
  // with bounds Ceres searches along every step for a better point inside them: on the cost alone
  // (the default cubic interpolation asks for the derivatives at every trial point, one more
  // Jacobian per iteration)
  o.line_search_interpolation_type = ceres::QUADRATIC;
  return o;
}

}  // namespace

// solveLocal (ceres_plugin.cpp) calls this through the plugin metrosync-ceres.so
LocalSolution solveLocalWithCeres(const LocalProblem& p) {
  const std::size_t k = p.start.size();
  if (p.scale.size() != k || p.lower.size() != k || p.held.size() != k || p.residual_count <= 0)
    throw std::invalid_argument("solveLocal: inconsistent problem");
  std::vector<double> x(k);
  for (std::size_t j = 0; j < k; ++j) x[j] = p.start[j] / p.scale[j];
  Functor f{&p, {}};
  std::vector<double*> blocks;
  for (std::size_t j = 0; j < k; ++j) {
    f.block_of.push_back(p.held[j] ? -1 : static_cast<int>(blocks.size()));
    if (!p.held[j]) blocks.push_back(&x[j]);
  }
  auto* cost = new ModelCost(f);
  for (std::size_t b = 0; b < blocks.size(); ++b) cost->addKey();
  cost->SetNumResiduals(p.residual_count);
  LocalSolution out{p.start, 0, true, ""};
  if (blocks.empty()) return delete cost, out;
  ceres::Problem problem;
  problem.AddResidualBlock(cost, p.loss_scale > 0 ? new ceres::CauchyLoss(p.loss_scale) : nullptr,
                           blocks);
  for (std::size_t j = 0, b = 0; j < k; ++j) {
    if (p.held[j]) continue;
    if (std::isfinite(p.lower[j]))
      problem.SetParameterLowerBound(blocks[b], 0, p.lower[j] / p.scale[j]);
    ++b;
  }
  // Ceres reports through glog on stderr ("Terminating: ..."): the command says it its own way
  FLAGS_minloglevel = google::GLOG_FATAL;
  LastAccepted last;
  last.x = &x;
  last.kept = x;
  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(p, &last), &problem, &summary);
  if (summary.termination_type == ceres::FAILURE && summary.iterations.empty())
    throw std::invalid_argument("the model fails at the starting values");
  if (summary.termination_type == ceres::FAILURE) x = last.kept;
  for (std::size_t j = 0; j < k; ++j)
    if (!p.held[j])
      out.values[j] = std::max(x[j] * p.scale[j], p.lower[j] + kInsideBound * p.scale[j]);
  out.iterations = static_cast<int>(summary.iterations.size());
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.report = summary.BriefReport();
  return out;
}

}  // namespace metrosync

extern "C" const metrosync::CeresPlugin* metrosync_ceres_plugin() {
  static const metrosync::CeresPlugin table{metrosync::kCeresPluginAbi,
                                            &metrosync::solveLocalWithCeres};
  return &table;
}
