#include "sim/analysis/fit/least_squares.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>

#include "sim/analysis/fit/ceres_plugin.h"

namespace metrosync {

namespace {

// Central-difference step, relative to the parameter (in units of its scale): the simulation's
// own relative error (simulation.accuracy, 1e-8 by default) stays 1e-4 below the differences.
constexpr double kDiffStep = 1e-4;
// A Jacobian column this small against the largest is zero: the data do not see the parameter.
constexpr double kZeroColumn = 1e-10;
// Eigenvalues of J^T J (scaled) below this fraction of the largest make it singular.
constexpr double kSingular = 1e-12;
// A standard error larger than this fraction of max(|value|, scale) determines nothing.
constexpr double kMaxRelativeError = 1.0;
// The solver stops when the cost changes by less than this fraction in a step.
constexpr double kFunctionTolerance = 1e-10;

// The weighted residuals as a function of the scaled parameters, counting model runs.
class Residuals {
 public:
  Residuals(const FitSetup& s, std::vector<double> group_weight)
      : s_(s), w_(std::move(group_weight)) {}

  std::vector<double> values(const double* x) const {
    std::vector<double> v(s_.free.size());
    for (std::size_t j = 0; j < v.size(); ++j) v[j] = x[j] * s_.free[j].scale;
    return v;
  }
  // false when the model fails there
  bool eval(const std::vector<double>& values, double* r) const {
    ++runs_;
    std::vector<double> p;
    try {
      p = s_.predict(values);
    } catch (const std::exception& e) {
      last_error_ = e.what();
      return false;
    }
    for (std::size_t i = 0; i < s_.observations.size(); ++i) {
      const Observation& o = s_.observations[i];
      r[i] = w_[o.group] * (p[i] - o.value);
      if (!std::isfinite(r[i])) return false;
    }
    return true;
  }
  int runs() const { return runs_; }
  const std::string& lastError() const { return last_error_; }

 private:
  const FitSetup& s_;
  std::vector<double> w_;
  mutable int runs_ = 0;
  mutable std::string last_error_;
};

// Ceres' functor: one parameter block of size 1 per free key (so that keys can be held).
struct Functor {
  const Residuals* res;
  std::vector<double>* x;     // the full scaled vector, held keys included
  std::vector<int> block_of;  // key j -> its block, -1 when held
  bool operator()(double const* const* blocks, double* r) const {
    std::vector<double> xx = *x;
    for (std::size_t j = 0; j < xx.size(); ++j)
      if (block_of[j] >= 0) xx[j] = blocks[block_of[j]][0];
    return res->eval(res->values(xx.data()), r);
  }
};

// Levenberg-Marquardt over the keys not held; x updated in place.
ceres::Solver::Summary solve(const FitSetup& s, const Residuals& res, std::vector<double>& x,
                             const std::vector<bool>& held) {
  ceres::NumericDiffOptions nd;
  nd.relative_step_size = kDiffStep;
  auto* f = new Functor{&res, &x, {}};
  auto* cost = new ceres::DynamicNumericDiffCostFunction<Functor, ceres::CENTRAL>(
      f, ceres::TAKE_OWNERSHIP, nd);
  std::vector<double*> blocks;
  for (std::size_t j = 0; j < x.size(); ++j) {
    f->block_of.push_back(held[j] ? -1 : static_cast<int>(blocks.size()));
    if (held[j]) continue;
    blocks.push_back(&x[j]);
    cost->AddParameterBlock(1);
  }
  cost->SetNumResiduals(static_cast<int>(s.observations.size()));
  ceres::Solver::Summary summary;
  if (blocks.empty()) return summary;
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, blocks);
  for (std::size_t j = 0, b = 0; j < x.size(); ++j) {
    if (held[j]) continue;
    if (std::isfinite(s.free[j].lower))
      problem.SetParameterLowerBound(blocks[b], 0, s.free[j].lower / s.free[j].scale);
    ++b;
  }
  // Ceres reports through glog on stderr ("Terminating: ..."): the command says it its own way
  FLAGS_minloglevel = google::GLOG_FATAL;
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = s.max_iterations;
  o.function_tolerance = kFunctionTolerance;
  o.logging_type = ceres::SILENT;
  // x holds the last accepted point even when the solve ends in FAILURE (a model that fails at a
  // step's derivative), rather than going back to the start
  o.update_state_every_iteration = true;
  ceres::Solve(o, &problem, &summary);
  return summary;
}

// Residuals at x and the central-difference Jacobian (all keys); a side where the model fails
// (a key at its bound) gives a one-sided difference. Throws when the model fails at x, or on
// both sides of it.
void jacobian(const Residuals& res, const std::vector<double>& x, int m, Eigen::VectorXd& r,
              Eigen::MatrixXd& J) {
  r.resize(m);
  J.resize(m, static_cast<int>(x.size()));
  if (!res.eval(res.values(x.data()), r.data())) throw std::invalid_argument(res.lastError());
  Eigen::VectorXd rp(m), rm(m);
  for (std::size_t j = 0; j < x.size(); ++j) {
    const double h = kDiffStep * std::max(std::abs(x[j]), 1.0);
    std::vector<double> xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    const bool plus = res.eval(res.values(xp.data()), rp.data());
    const bool minus = res.eval(res.values(xm.data()), rm.data());
    if (!plus && !minus) throw std::invalid_argument(res.lastError());
    const int c = static_cast<int>(j);
    if (plus && minus)
      J.col(c) = (rp - rm) / (2 * h);
    else if (plus)
      J.col(c) = (rp - r) / h;
    else
      J.col(c) = (r - rm) / h;
  }
}

// Keys whose Jacobian column is (numerically) zero.
std::vector<bool> zeroColumns(const Eigen::MatrixXd& J) {
  double largest = 0.0;
  for (int j = 0; j < J.cols(); ++j) largest = std::max(largest, J.col(j).norm());
  std::vector<bool> zero(J.cols());
  for (int j = 0; j < J.cols(); ++j) zero[j] = !(J.col(j).norm() > kZeroColumn * largest);
  return zero;
}

// The key the data determine least among those not held (-1: all are determined), from the
// scaled Jacobian J and residuals r: a direction of J^T J with a vanishing eigenvalue (blamed on
// its largest component), else the largest standard error beyond kMaxRelativeError.
int leastDetermined(const Eigen::MatrixXd& J, const Eigen::VectorXd& r,
                    const std::vector<double>& x, const std::vector<bool>& held,
                    Eigen::MatrixXd& cov) {
  std::vector<int> f;
  for (std::size_t j = 0; j < held.size(); ++j)
    if (!held[j]) f.push_back(static_cast<int>(j));
  if (f.empty()) return -1;
  const int n = static_cast<int>(f.size()), m = static_cast<int>(r.size());
  Eigen::MatrixXd Jf(m, n);
  for (int a = 0; a < n; ++a) Jf.col(a) = J.col(f[a]);
  const Eigen::MatrixXd A = Jf.transpose() * Jf;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  const double top = eig.eigenvalues().maxCoeff();
  if (!(eig.eigenvalues()(0) > kSingular * top)) {
    int worst = 0;
    eig.eigenvectors().col(0).cwiseAbs().maxCoeff(&worst);
    return f[worst];
  }
  const double sigma2 = r.squaredNorm() / std::max(1, m - n);
  const Eigen::MatrixXd c = sigma2 * A.inverse();
  cov = Eigen::MatrixXd::Zero(x.size(), x.size());
  int worst = -1;
  double worst_rel = kMaxRelativeError;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) cov(f[a], f[b]) = c(a, b);
    const double rel = std::sqrt(c(a, a)) / std::max(std::abs(x[f[a]]), 1.0);
    if (rel > worst_rel) worst_rel = rel, worst = f[a];
  }
  return worst;
}

std::vector<double> groupRms(const FitSetup& s, const std::vector<double>& predicted, int groups,
                             bool by_quantity) {
  const int n = by_quantity ? static_cast<int>(s.quantity_names.size()) : groups;
  std::vector<double> sum(n, 0.0), count(n, 0.0);
  for (std::size_t i = 0; i < s.observations.size(); ++i) {
    const Observation& o = s.observations[i];
    const int g = by_quantity ? o.quantity : o.group;
    sum[g] += (predicted[i] - o.value) * (predicted[i] - o.value);
    count[g] += 1;
  }
  for (int g = 0; g < n; ++g) sum[g] = count[g] > 0 ? std::sqrt(sum[g] / count[g]) : 0.0;
  return sum;
}

int groupCount(const FitSetup& s) {
  int g = 0;
  for (const Observation& o : s.observations) g = std::max(g, o.group + 1);
  return g;
}

// The fitted model's residuals per group, as weights for a second pass (a group that fits
// exactly keeps weight 1).
std::vector<double> weightsFromResiduals(const FitSetup& s, const std::vector<double>& x, int g,
                                         int& runs) {
  std::vector<double> v(x.size());
  for (std::size_t j = 0; j < x.size(); ++j) v[j] = x[j] * s.free[j].scale;
  ++runs;
  const std::vector<double> rms = groupRms(s, s.predict(v), g, false);
  std::vector<double> w(g, 1.0);
  for (int k = 0; k < g; ++k)
    if (rms[k] > 0) w[k] = 1.0 / rms[k];
  return w;
}

FitResult results(const FitSetup& s, const std::vector<double>& x, const std::vector<bool>& held,
                  const Eigen::MatrixXd& cov) {
  const std::size_t k = x.size();
  FitResult out;
  out.values.resize(k);
  out.std_errors.resize(k);
  out.correlation.assign(k, std::vector<std::optional<double>>(k));
  for (std::size_t j = 0; j < k; ++j) {
    out.used.push_back(x[j] * s.free[j].scale);
    out.identifiable.push_back(!held[j]);
    if (held[j]) continue;
    out.values[j] = out.used[j];
    out.std_errors[j] = std::sqrt(cov(j, j)) * s.free[j].scale;
    for (std::size_t i = 0; i < k; ++i)
      if (!held[i]) out.correlation[j][i] = cov(j, i) / std::sqrt(cov(j, j) * cov(i, i));
  }
  out.predicted = s.predict(out.used);
  out.rms = groupRms(s, out.predicted, groupCount(s), false).at(0);
  out.rms_by_quantity = groupRms(s, out.predicted, 0, true);
  return out;
}

}  // namespace

// fitLeastSquares (ceres_plugin.cpp) calls this through the plugin metrosync-ceres.so
FitResult fitLeastSquaresWithCeres(const FitSetup& s) {
  const std::size_t k = s.free.size(), m = s.observations.size();
  if (k == 0 || m <= k)
    throw std::invalid_argument(std::to_string(m) + " observations for " + std::to_string(k) +
                                " free keys: more observations than keys are needed");
  std::vector<double> x(k);
  for (std::size_t j = 0; j < k; ++j) x[j] = s.free[j].start / s.free[j].scale;
  const int g = groupCount(s);
  int runs = 0;
  auto residuals = std::make_unique<Residuals>(s, std::vector<double>(g, 1.0));
  Eigen::VectorXd r;
  Eigen::MatrixXd J, cov;
  // keys the data do not see at the start are held there
  jacobian(*residuals, x, static_cast<int>(m), r, J);
  std::vector<bool> held = zeroColumns(J);
  ceres::Solver::Summary summary = solve(s, *residuals, x, held);
  if (g > 1) {  // angles and lengths: each group weighted by its own residual level
    runs += residuals->runs();
    residuals = std::make_unique<Residuals>(s, weightsFromResiduals(s, x, g, runs));
    summary = solve(s, *residuals, x, held);
  }
  // a key the optimum does not determine is held at its start, and the rest fitted again
  for (std::size_t pass = 0; pass < k; ++pass) {
    jacobian(*residuals, x, static_cast<int>(m), r, J);
    const int worst = leastDetermined(J, r, x, held, cov);
    if (worst < 0) break;
    held[worst] = true;
    x[worst] = s.free[worst].start / s.free[worst].scale;
    summary = solve(s, *residuals, x, held);
  }
  FitResult out = results(s, x, held, cov);
  out.evaluations = runs + residuals->runs() + 1;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.solver_summary = summary.BriefReport();
  return out;
}

}  // namespace metrosync

extern "C" const metrosync::CeresPlugin* metrosync_ceres_plugin() {
  static const metrosync::CeresPlugin table{metrosync::kCeresPluginAbi,
                                            &metrosync::fitLeastSquaresWithCeres};
  return &table;
}
