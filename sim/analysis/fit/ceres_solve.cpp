// The Ceres plugin's body (sim/analysis/fit/ceres_plugin.h): solveLocal's least squares
// (sim/analysis/fit/least_squares.h) by Ceres Solver.
#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <stdexcept>

#include "sim/analysis/fit/ceres_plugin.h"

namespace metrosync {

namespace {

// Central-difference step, relative to the parameter (in units of its scale): the simulation's
// own relative error (simulation.accuracy, 1e-8 by default) stays 1e-4 below the differences.
constexpr double kDiffStep = 1e-4;
// The solver stops when the cost changes by less than this fraction in a step.
constexpr double kFunctionTolerance = 1e-10;
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
  bool operator()(double const* const* blocks, double* r) const {
    std::vector<double> v = p->start;
    for (std::size_t j = 0; j < v.size(); ++j)
      if (block_of[j] >= 0)
        v[j] = std::max(blocks[block_of[j]][0] * p->scale[j],
                        p->lower[j] + kInsideBound * p->scale[j]);
    try {
      if (!p->residuals(v, r)) return false;
    } catch (const std::exception&) {
      return false;
    }
    for (int i = 0; i < p->residual_count; ++i)
      if (!std::isfinite(r[i])) return false;
    return true;
  }
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
  ceres::NumericDiffOptions nd;
  nd.relative_step_size = kDiffStep;
  auto* f = new Functor{&p, {}};
  auto* cost = new ceres::DynamicNumericDiffCostFunction<Functor, ceres::CENTRAL>(
      f, ceres::TAKE_OWNERSHIP, nd);
  std::vector<double*> blocks;
  for (std::size_t j = 0; j < k; ++j) {
    f->block_of.push_back(p.held[j] ? -1 : static_cast<int>(blocks.size()));
    if (p.held[j]) continue;
    blocks.push_back(&x[j]);
    cost->AddParameterBlock(1);
  }
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
