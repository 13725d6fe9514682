#include "sim/analysis/fit/fit_strategy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "base/constants.h"
#include "base/number_text.h"
#include "models/scaling.h"
#include "sim/analysis/fit/fit_observations.h"
#include "sim/analysis/fit/fit_statistics.h"
#include "sim/analysis/fit/fit_verdict.h"
#include "sim/analysis/fit/key_directions.h"
#include "sim/analysis/fit/least_squares.h"
#include "sim/analysis/fit/likelihood_region.h"
#include "sim/analysis/fit/model_jacobian.h"
#include "sim/analysis/fit/model_samples.h"

namespace metrosync {

namespace {

// The first window of the samples: two periods, over which a model tens of percent off in its
// amplitude (and so its frequency) stays well inside a half period of the data. (Eight periods
// were too many: from starts 40% off, 1 record in 12 of docs/bench/fit.md fell into a wrong
// optimum there.)
constexpr double kFirstWindowPeriods = 2.0;
// Iterations of each window's solve (each starts close to its optimum).
constexpr int kWindowIterations = 20;
// The windows' prior: each key's deviation from the last window's value in units of this much of
// its scale counts as one noise level, so that a key a short window does not yet determine stays
// where it was (friction over two periods of nearly antiphase swings) instead of wandering to a
// bound.
constexpr double kPriorWidth = 0.5;
// Cauchy's loss on the windows at this many noise levels: an out-of-phase stretch (residuals of
// the swing's size, hundreds of noise levels) pulls little, a fitting one fully.
constexpr double kLossNoises = 3.0;
// The search stops after this many starts in a row that lead to optima already found.
constexpr int kStartsInVain = 2;
// The search's test of a start in vain: it led into a valley already found when every key agrees
// to this fraction of its scale with an optimum found, and the rms too.
constexpr double kSameOptimum = 1e-3;
// Two optima are one (the same minimum, solved twice) when every key agrees to this fraction of
// its scale: the solver's own precision (its parameter tolerance, 1e-8), far below a standard
// error. Coarser would be wrong: a long record's standard errors reach 4e-5 of a key
// (docs/bench/fit.md, seed 2's record 7), and neighbouring optima a few of them apart are what
// the likelihood region (likelihood_region.h) is made of; kSameOptimum would merge them.
constexpr double kSameMinimum = 1e-6;
// The profile's points, in standard errors, and the least rise of the sum of squares there (in
// its variance) that still determines the key (a linear model rises by 4).
constexpr double kProfileSigmas = 2.0;
constexpr double kProfileMinRise = 1.0;

// The observations, the model that predicts them, and the residual functions of each stage.
class ModelFit {
 public:
  ModelFit(const FitProblem& p, const Rig& start_rig) : p_(p) {
    std::vector<double> theta_c;
    for (const MetronomeSpec& m : start_rig.metronomes) theta_c.push_back(m.theta_c_rad);
    d_ = fitData(*p.data, slow(), theta_c, p.settings.noise);
    period_ = 2 * kPi * computeScaled(start_rig).time_scale_s;
    row_dt_ = modelRowInterval(p.data->t_s, start_rig);
    t_end_ = d_.observations.back().t_s;
    weighted_ = true;
    for (std::size_t q = 0; q < d_.noise.size(); ++q) {
      weight_.push_back(d_.noise[q] > 0 ? 1.0 / d_.noise[q] : 1.0);
      weighted_ = weighted_ && d_.noise[q] > 0;
    }
    exact_ = exactDerivatives(start_rig);
  }
  bool slow() const { return p_.settings.model == "slow"; }
  const FitData& data() const { return d_; }
  double period() const { return period_; }
  double end() const { return t_end_; }
  int runs() const { return runs_; }
  int jacobians() const { return jacobians_; }
  bool weighted() const { return weighted_; }

  // observations at t <= t_window (a prefix: they are in time order)
  int observations(double t_window) const {
    const auto& o = d_.observations;
    return static_cast<int>(
        std::upper_bound(o.begin(), o.end(), t_window,
                         [](double t, const Observation& b) { return t < b.t_s; }) -
        o.begin());
  }
  // the model at the first n observations
  std::vector<double> predict(const std::vector<double>& v, int n) const {
    const std::vector<Observation>& o = d_.observations;
    std::vector<double> out(n);
    if (slow()) {
      ++runs_;
      std::vector<SampleRequest> req;
      for (int i = 0; i < n; ++i) req.push_back({o[i].t_s, d_.metronome[o[i].quantity]});
      return sampleSlowFlow(*p_.engine, p_.rig(v), req);
    }
    const std::shared_ptr<const ModelTrajectory> traj = run(v, n);
    for (int i = 0; i < n; ++i) out[i] = traj->at(o[i].t_s, d_.metronome[o[i].quantity]);
    return out;
  }
  // weighted residuals of the first n observations
  ResidualFunction samples(int n) const {
    return [this, n](const std::vector<double>& v, double* r) {
      std::vector<double> m;
      try {
        m = predict(v, n);
      } catch (const std::exception&) {
        return false;  // the model fails there
      }
      weigh(m, n, r);
      return true;
    };
  }
  // the same with their exact derivatives in the keys not held (model_jacobian.h); empty where the
  // model has none (the slow flow): the solver differences the residuals instead
  JacobianFunction derivatives(int n, const std::vector<bool>& held) const {
    if (!exact_) return {};
    std::vector<bool> wanted(held.size());
    for (std::size_t j = 0; j < held.size(); ++j) wanted[j] = !held[j];
    return [this, n, wanted](const std::vector<double>& v, double* r, double* J) {
      orbit::Mat D;
      std::vector<double> m;
      try {
        m = predict(v, n);  // the run the derivatives take their events from
        D = modelJacobian(p_, v, *last_, d_, n, wanted);
      } catch (const std::exception&) {
        return false;  // the model fails there
      }
      ++jacobians_;
      weigh(m, n, r);
      for (int j = 0; j < D.cols(); ++j)
        for (int i = 0; i < n; ++i) J[j * n + i] = weight_[d_.observations[i].quantity] * D(i, j);
      return true;
    };
  }

 private:
  // r_i = (model_i - value_i) / noise of its column
  void weigh(const std::vector<double>& m, int n, double* r) const {
    for (int i = 0; i < n; ++i) {
      const Observation& o = d_.observations[i];
      r[i] = weight_[o.quantity] * (m[i] - o.value);
    }
  }
  // The model's run at v to the n-th observation. The last one is kept: the solver asks for the
  // residuals at a point and then, when it keeps the point, for their derivatives there.
  std::shared_ptr<const ModelTrajectory> run(const std::vector<double>& v, int n) const {
    if (last_ && last_values_ == v && last_n_ == n) return last_;
    last_.reset();
    ++runs_;
    last_ = std::make_shared<const ModelTrajectory>(*p_.engine, p_.rig(v),
                                                    d_.observations[n - 1].t_s, row_dt_);
    last_values_ = v;
    last_n_ = n;
    return last_;
  }
  // The full model with a law that gives its partials and keys that move only its constants
  // (key_directions.h): exact derivatives.
  bool exactDerivatives(const Rig& start_rig) const {
    if (slow() || !hasModelJacobian(p_, start_rig)) return false;
    std::vector<double> start;
    for (const FreeParameter& f : p_.free) start.push_back(f.start);
    try {
      keyDirections(p_, start, std::vector<bool>(start.size(), true),
                    orbit::PhysicalModel(start_rig));
    } catch (const std::exception&) {
      return false;
    }
    return true;
  }

  const FitProblem& p_;
  FitData d_;
  double period_ = 1.0, row_dt_ = 0.01, t_end_ = 0.0;
  std::vector<double> weight_;  // per quantity: 1 / noise (1 where it is not known)
  bool weighted_ = false;       // every quantity's noise known: residuals in noise levels
  bool exact_ = false;          // the model's exact derivatives (else differences)
  mutable int runs_ = 0, jacobians_ = 0;
  mutable std::shared_ptr<const ModelTrajectory> last_;
  mutable std::vector<double> last_values_;
  mutable int last_n_ = 0;
};

LocalProblem localProblem(const FitProblem& p, const ResidualFunction& f,
                          const JacobianFunction& jac, int m, const std::vector<double>& start,
                          const std::vector<bool>& held, int iterations, double loss) {
  LocalProblem lp;
  lp.residuals = f;
  lp.jacobian = jac;
  lp.residual_count = m;
  lp.start = start;
  for (const FreeParameter& fp : p.free) {
    lp.scale.push_back(fp.scale);
    lp.lower.push_back(fp.lower);
  }
  lp.held = held;
  lp.max_iterations = iterations;
  lp.loss_scale = loss;
  return lp;
}

// The rms of the residuals per quantity.
std::vector<double> rmsByQuantity(const FitData& d, const std::vector<double>& predicted) {
  std::vector<double> sum(d.quantity_names.size(), 0.0), count(sum.size(), 0.0);
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const Observation& o = d.observations[i];
    sum[o.quantity] += (predicted[i] - o.value) * (predicted[i] - o.value);
    count[o.quantity] += 1;
  }
  for (std::size_t q = 0; q < sum.size(); ++q)
    sum[q] = count[q] > 0 ? std::sqrt(sum[q] / count[q]) : 0.0;
  return sum;
}

// The rms of the first group's residuals (the angles, or x when it is all there is).
double firstGroupRms(const FitData& d, const std::vector<double>& predicted) {
  double sum = 0.0, count = 0.0;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const Observation& o = d.observations[i];
    if (o.group != 0) continue;
    sum += (predicted[i] - o.value) * (predicted[i] - o.value);
    count += 1;
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

// The further starts of a key that cannot be negative alternate between [start / kNearSpread,
// kNearSpread start] (odd ones: a key the phase is very sensitive to, a pendulum's length 33%
// off, is found from there, rarely from farther) and [start / kFarSpread, kFarSpread start] (even
// ones: a start 70% below its truth is 3.3 times below it, which the near spread never reaches).
constexpr double kNearSpread = 2.0;
constexpr double kFarSpread = 4.0;

// The starting points: the given one, then a Halton sequence (bases 2, 3, 5, ...) over the
// spreads above of each key that cannot be negative, start -+ 2 scale of the others.
std::vector<double> startingPoint(const FitProblem& p, int index) {
  static const int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53};
  std::vector<double> x;
  for (std::size_t j = 0; j < p.free.size(); ++j) {
    const FreeParameter& f = p.free[j];
    if (index == 0) {
      x.push_back(f.start);
      continue;
    }
    const int base = kPrimes[j % 16];
    double h = 0.0, w = 1.0;  // radical inverse of index + seed in `base`
    for (unsigned n = index + p.settings.seed * 7; n > 0; n /= base) h += (w /= base) * (n % base);
    const double u = 2 * h - 1;  // in [-1, 1)
    const double spread = index % 2 ? kNearSpread : kFarSpread;
    x.push_back(f.lower >= 0 ? (f.start > 0 ? f.start : f.scale) * std::pow(spread, u)
                             : f.start + 2 * u * f.scale);
  }
  return x;
}

// The section-3 shortcuts' starting point (FreeParameter::shortcut; the given start for a key
// without one), or nothing when no key has one that differs from its start.
std::optional<std::vector<double>> shortcutPoint(const FitProblem& p) {
  std::vector<double> x;
  bool differs = false;
  for (const FreeParameter& f : p.free) {
    x.push_back(f.shortcut.value_or(f.start));
    differs = differs || x.back() != f.start;
  }
  if (!differs) return std::nullopt;
  return x;
}

// f with one more residual per parameter: (value - centre) / (width scale), a weak prior that
// keeps a key the window does not yet determine where it was.
ResidualFunction withPrior(const FitProblem& p, ResidualFunction f, int n,
                           std::vector<double> centre, double width) {
  return [&p, f, n, centre, width](const std::vector<double>& v, double* r) {
    if (!f(v, r)) return false;
    for (std::size_t j = 0; j < v.size(); ++j)
      r[n + j] = (v[j] - centre[j]) / (width * p.free[j].scale);
    return true;
  };
}
// ... and its derivatives: the model's rows, then 1 / (width scale) on the diagonal
JacobianFunction withPrior(const FitProblem& p, JacobianFunction jac, int n,
                           std::vector<double> centre, double width) {
  if (!jac) return {};
  return [&p, jac, n, centre, width](const std::vector<double>& v, double* r, double* J) {
    const int k = static_cast<int>(v.size());
    std::vector<double> inner(static_cast<std::size_t>(n) * k);
    if (!jac(v, r, inner.data())) return false;
    for (int j = 0; j < k; ++j) {
      std::copy(inner.begin() + j * n, inner.begin() + (j + 1) * n, J + j * (n + k));
      for (int l = 0; l < k; ++l)
        J[j * (n + k) + n + l] = l == j ? 1 / (width * p.free[j].scale) : 0;
      r[n + j] = (v[j] - centre[j]) / (width * p.free[j].scale);
    }
    return true;
  };
}

// Steps 1-2 of fit_strategy.h from x.
LocalSolution searchFrom(const FitProblem& p, const ModelFit& mf, std::vector<double> x,
                         const std::vector<bool>& held, std::string& strategy) {
  int fitted = 0;
  for (bool h : held) fitted += !h;
  const int k = static_cast<int>(x.size());
  const int all = static_cast<int>(mf.data().observations.size());
  strategy.clear();
  if (!mf.slow() && !p.settings.local) {
    const double loss = mf.weighted() ? kLossNoises : 0.0;
    std::string windows;
    for (double T = kFirstWindowPeriods * mf.period(); T < mf.end(); T *= 2) {
      const int n = mf.observations(T);
      if (n <= fitted) continue;
      const ResidualFunction f = withPrior(p, mf.samples(n), n, x, kPriorWidth);
      const JacobianFunction jac = withPrior(p, mf.derivatives(n, held), n, x, kPriorWidth);
      x = solveLocal(localProblem(p, f, jac, n + k, x, held, kWindowIterations, loss)).values;
      windows += (windows.empty() ? "" : ", ") + numberText(T, 3);
    }
    if (!windows.empty()) strategy = "windows of " + windows + " s, then ";
  }
  strategy += mf.slow() ? "the swings' amplitudes" : "the whole record";
  return solveLocal(localProblem(p, mf.samples(all), mf.derivatives(all, held), all, x, held,
                                 p.settings.max_iterations, 0));
}

Optimum optimumOf(const ModelFit& mf, const std::vector<double>& start,
                  const std::vector<double>& x) {
  const int all = static_cast<int>(mf.data().observations.size());
  const std::vector<double> predicted = mf.predict(x, all);
  return {x, start, firstGroupRms(mf.data(), predicted),
          atNoiseLevel(rmsByQuantity(mf.data(), predicted), mf.data().noise)};
}

// a and b agree to `fraction` of each key's scale (and of their rms)
bool sameOptimum(const FitProblem& p, const Optimum& a, const Optimum& b,
                 double fraction = kSameOptimum) {
  if (!(std::abs(a.rms - b.rms) <= fraction * std::max(a.rms, b.rms))) return false;
  for (std::size_t j = 0; j < p.free.size(); ++j)
    if (!(std::abs(a.values[j] - b.values[j]) <= fraction * p.free[j].scale)) return false;
  return true;
}

// What the final stage needs again and again: the whole record's residuals (and derivatives).
struct Final {
  const FitProblem& p;
  const ModelFit& mf;
  int m;
  ResidualFunction f;
  Final(const FitProblem& p, const ModelFit& mf)
      : p(p), mf(mf), m(static_cast<int>(mf.data().observations.size())), f(mf.samples(m)) {}
  LocalSolution solve(const std::vector<double>& x, const std::vector<bool>& held) const {
    return solveLocal(
        localProblem(p, f, mf.derivatives(m, held), m, x, held, p.settings.max_iterations, 0));
  }
  Linearization linearization(const std::vector<double>& x, const std::vector<bool>& held,
                              bool find_smooth) const {
    return linearize(f, m, x, p.free, find_smooth, mf.derivatives(m, held));
  }
  double ssr(const std::vector<double>& x) const {
    std::vector<double> r(m);
    return f(x, r.data()) ? Eigen::Map<Eigen::VectorXd>(r.data(), m).squaredNorm() : HUGE_VAL;
  }
};

// Key j held at x_j -+ kProfileSigmas standard errors, the others fitted again.
Profile profileOf(const Final& fin, const std::vector<double>& x, std::vector<bool> held, int j,
                  double sd, double sigma2) {
  const double base = fin.ssr(x);
  held[j] = true;
  Profile pr;
  double* at[2] = {&pr.lower_at, &pr.upper_at};
  double* rise[2] = {&pr.lower_rise, &pr.upper_rise};
  for (int side = 0; side < 2; ++side) {
    std::vector<double> y = x;
    y[j] = x[j] + (side ? 1 : -1) * kProfileSigmas * sd;
    if (fin.p.free[j].lower > y[j]) y[j] = fin.p.free[j].lower;
    *at[side] = y[j];
    try {
      *rise[side] = (fin.ssr(fin.solve(y, held).values) - base) / sigma2;
    } catch (const std::exception&) {  // the model fails there: the data rule it out
      *rise[side] = HUGE_VAL;
    }
  }
  return pr;
}

// The hold loop of fit_strategy.h at the best optimum: fills values, errors, correlations,
// profiles, identifiability; x and held updated.
void determine(const Final& fin, std::vector<double>& x, std::vector<bool>& held,
               LocalSolution& sol, FitOutcome& out) {
  const std::vector<FreeParameter>& free = fin.p.free;
  const bool profile = fin.p.settings.profile || fin.mf.slow();
  for (std::size_t pass = 0; pass <= free.size(); ++pass) {
    const Linearization lin = fin.linearization(x, held, true);
    const Uncertainty u = uncertainty(lin, x, free, held);
    out.smooth_until_s = lin.smooth_rows < fin.m && lin.smooth_rows > 0
                             ? fin.mf.data().observations[lin.smooth_rows - 1].t_s
                         : lin.smooth_rows == 0 ? 0.0
                                                : std::nan("");
    int worst = u.worst;
    std::string why = u.why;
    out.profiles.assign(free.size(), std::nullopt);
    for (std::size_t j = 0; worst < 0 && profile && j < free.size(); ++j) {
      if (held[j] || !u.std_errors[j]) continue;
      out.profiles[j] = profileOf(fin, x, held, j, *u.std_errors[j], u.sigma2);
      const double r = std::min(out.profiles[j]->lower_rise, out.profiles[j]->upper_rise);
      if (r < kProfileMinRise)
        worst = j, why = "its profile is flat: the sum of squares rises by only " +
                         numberText(r, 3) + " variances at " + numberText(kProfileSigmas, 3) +
                         " standard errors";
    }
    if (worst < 0) {
      out.std_errors = u.std_errors;
      out.correlation = u.correlation;
      out.singular_values = u.singular_values;
      return;
    }
    // held where the fit put it (the data cannot tell it from there, and the model fits there)
    held[worst] = true;
    out.not_identifiable_because[worst] = why;
    sol = fin.solve(x, held);
    x = sol.values;
  }
}

// An optimum with what led to it.
struct Candidate {
  Optimum optimum;
  LocalSolution solution;
  std::string strategy;
};

// c's optimum is not in `found` yet (kSameMinimum)
bool isNew(const FitProblem& p, const std::vector<Candidate>& found, const Candidate& c) {
  for (const Candidate& f : found)
    if (sameOptimum(p, f.optimum, c.optimum, kSameMinimum)) return false;
  return true;
}

// Every distinct optimum from the starting points of fit_strategy.h, best first.
std::vector<Candidate> search(const FitProblem& p, const ModelFit& mf,
                              const std::vector<bool>& held) {
  std::vector<Candidate> found;
  const std::optional<std::vector<double>> shortcut = shortcutPoint(p);
  int in_vain = 0;  // starts in a row that found no new optimum
  for (int s = 0; s < std::max(1, p.settings.starts) && in_vain < kStartsInVain; ++s) {
    // the given start, the shortcuts' (when a --set start hides one), then the Halton points
    const std::vector<double> x0 =
        shortcut && s == 1 ? *shortcut : startingPoint(p, shortcut && s > 1 ? s - 1 : s);
    Candidate c;
    try {
      c.solution = searchFrom(p, mf, x0, held, c.strategy);
    } catch (const std::exception&) {
      if (s == 0) throw;
      continue;  // the model fails at this starting point: the next
    }
    c.optimum = optimumOf(mf, x0, c.solution.values);
    const bool at_noise = c.optimum.at_noise;
    bool known = false;
    for (const Candidate& f : found) known = known || sameOptimum(p, f.optimum, c.optimum);
    in_vain = known ? in_vain + 1 : 0;
    if (isNew(p, found, c)) found.push_back(std::move(c));
    if (at_noise) break;
  }
  std::stable_sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
    return a.optimum.rms < b.optimum.rms;
  });
  return found;
}

// The probes' distances along each principal axis, in standard deviations.
constexpr double kProbeSigmas[] = {-4.0, -2.0, 2.0, 4.0};

// Adds the optimum solved from y to `found` unless it is one already there.
void solveFrom(const FitProblem& p, const ModelFit& mf, const Final& fin,
               const std::vector<bool>& held, const std::vector<double>& y, const char* how,
               std::vector<Candidate>& found) {
  Candidate c;
  try {
    c.solution = fin.solve(y, held);
    c.optimum = optimumOf(mf, y, c.solution.values);
  } catch (const std::exception&) {
    return;  // the model fails on the way: no optimum there
  }
  c.strategy = found.front().strategy + how;
  if (isNew(p, found, c)) found.push_back(c);
}

// x moved `sigmas` standard deviations along the covariance's principal axis `axis` (its keys'
// lower bounds kept)
std::vector<double> along(const std::vector<double>& x,
                          const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eig,
                          std::size_t axis, double sigmas, const FitProblem& p) {
  std::vector<double> y = x;
  const double sd = std::sqrt(std::max(eig.eigenvalues()(axis), 0.0));
  for (std::size_t j = 0; j < x.size(); ++j)
    y[j] = std::max(x[j] + sigmas * sd * eig.eigenvectors()(j, axis), p.free[j].lower);
  return y;
}

// A probe along the weakest axis whose rise (in variances) is below this share of the quadratic
// cost's (sigmas^2) shows a neighbouring valley there. On the benchmark's records the probes rise
// by 0.97-1.00 of the quadratic's (docs/bench/fit.md): the exact derivatives' covariance has the
// valley's shape right out to 4 standard deviations.
constexpr double kQuadraticShare = 0.5;

// Probes around the best optimum along each principal axis of its covariance, at -+2 and -+4
// standard deviations (no solve: one model run each). Where a long record makes the cost rugged a
// lower optimum can lie a few standard deviations away behind a ridge; a probe lower than the
// optimum is solved from. Along the weakest axis (the largest variance: on the benchmark's
// records a metronome's damping and impulse together) neighbouring optima at the noise level lie
// when there are any, and the likelihood region (likelihood_region.h) needs them: from a probe
// there that rises less than the quadratic cost would (kQuadraticShare) the whole record is
// solved again. (Issue 27's differenced solver was solved again from every probe there: what that
// found on the benchmark's records was the same minimum stopped short of by a few 1e-4 standard
// errors, tests/fit's OneMinimumWhereTheCostIsQuadratic.) What they reach joins the list.
void probe(const FitProblem& p, const ModelFit& mf, const Final& fin, const std::vector<bool>& held,
           std::vector<Candidate>& found) {
  const std::vector<double> x = found.front().optimum.values;
  const std::size_t k = x.size();
  Uncertainty u;
  try {
    u = uncertainty(fin.linearization(x, held, false), x, p.free, held);
  } catch (const std::exception&) {
    return;
  }
  if (u.worst >= 0) return;  // a key undetermined: the hold loop's business
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(k, k);
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = 0; b < k; ++b)
      if (u.std_errors[a] && u.std_errors[b] && u.correlation[a][b])
        cov(a, b) = *u.std_errors[a] * *u.std_errors[b] * *u.correlation[a][b];
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);  // eigenvalues ascending
  const double base = fin.ssr(x);
  double best = base;
  std::vector<double> lowest;
  std::vector<std::vector<double>> valleys;
  for (std::size_t axis = 0; axis < k; ++axis)
    for (const double sigmas : kProbeSigmas) {
      const std::vector<double> y = along(x, eig, axis, sigmas, p);
      const double s = fin.ssr(y);
      if (axis + 1 == k && (s - base) / u.sigma2 < kQuadraticShare * sigmas * sigmas)
        valleys.push_back(y);
      if (s < best) best = s, lowest = y;
    }
  if (!lowest.empty()) solveFrom(p, mf, fin, held, lowest, ", then a probe around it", found);
  for (const std::vector<double>& y : valleys)
    if (y != lowest)
      solveFrom(p, mf, fin, held, y, ", then a restart along its weakest direction", found);
  std::stable_sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
    return a.optimum.rms < b.optimum.rms;
  });
}

// Each optimum's rise above the best x (in variances), and each key's interval over the
// likelihood region and its standard error (likelihood_region.h). Only when no key is held: an
// optimum found with every key free is not comparable with a best refitted with one held.
void region(const FitProblem& p, const Final& fin, const std::vector<double>& x,
            const std::vector<bool>& held, FitOutcome& out) {
  const std::size_t k = x.size();
  out.curvature_std_errors = out.std_errors;
  out.intervals.assign(k, std::nullopt);
  out.std_error_from.assign(k, "");
  for (std::size_t j = 0; j < k; ++j)
    if (out.std_errors[j] && !held[j]) out.std_error_from[j] = "curvature";
  if (std::find(held.begin(), held.end(), true) != held.end()) return;
  const double best = fin.ssr(x), sigma2 = best / (fin.m - static_cast<double>(k));
  std::vector<RegionOptimum> others;
  for (Optimum& o : out.optima) {
    o.rise = o.values == x ? 0.0 : (fin.ssr(o.values) - best) / sigma2;
    if (o.values != x) others.push_back({o.values, o.rise});
  }
  std::vector<double> lower;
  for (const FreeParameter& f : p.free) lower.push_back(f.lower);
  const auto iv = likelihoodIntervals(x, out.std_errors, others, lower);
  for (std::size_t j = 0; j < k; ++j) {
    if (!iv[j]) continue;
    out.intervals[j] = std::make_pair(iv[j]->lower, iv[j]->upper);
    out.std_errors[j] = iv[j]->std_error;
    out.std_error_from[j] = iv[j]->from_optima ? "optima" : "curvature";
  }
}

// The outcome's values, residuals, noise and verdict at x.
void describe(const ModelFit& mf, const std::vector<double>& x, const std::vector<bool>& held,
              const LocalSolution& best, FitOutcome& out) {
  const std::size_t k = x.size();
  out.values.assign(k, std::nullopt);
  for (std::size_t j = 0; j < k; ++j) {
    out.identifiable.push_back(!held[j]);
    out.used.push_back(x[j]);
    if (!held[j]) out.values[j] = x[j];
    if (held[j]) out.std_errors[j].reset();
  }
  const FitData& d = mf.data();
  out.quantity_names = d.quantity_names;
  out.observations = d.observations;
  out.predicted = mf.predict(x, static_cast<int>(d.observations.size()));
  out.rms = firstGroupRms(d, out.predicted);
  out.rms_by_quantity = rmsByQuantity(d, out.predicted);
  out.noise_by_quantity = d.noise;
  out.noise_from = d.noise_from;
  out.evaluations = mf.runs();
  out.jacobians = mf.jacobians();
  out.iterations = best.iterations;
  out.solver_converged = best.converged;
  out.solver_summary = best.report;
  judgeFit(out, d.noise_reliable, mf.slow());
}

}  // namespace

FitOutcome fitModel(const FitProblem& p) {
  const std::size_t k = p.free.size();
  std::vector<double> start;
  for (const FreeParameter& f : p.free) start.push_back(f.start);
  const ModelFit mf(p, p.rig(start));
  const Final fin(p, mf);
  if (k == 0 || static_cast<std::size_t>(fin.m) <= k)
    throw std::invalid_argument(std::to_string(fin.m) + " observations for " + std::to_string(k) +
                                " free keys: more observations than keys are needed");
  mf.predict(start, fin.m);  // throws ModelFailure when the model fails at the start
  FitOutcome out;
  out.warnings = mf.data().warnings;
  out.not_identifiable_because.assign(k, "");
  // keys the data do not see at the start are held there
  std::vector<bool> held = unseenKeys(fin.linearization(start, std::vector<bool>(k), false).J);
  for (std::size_t j = 0; j < k; ++j)
    if (held[j]) out.not_identifiable_because[j] = "the data do not see it";
  std::vector<Candidate> found = search(p, mf, held);
  probe(p, mf, fin, held, found);
  for (const Candidate& c : found) out.optima.push_back(c.optimum);
  LocalSolution best = found.front().solution;
  out.strategy = found.front().strategy;
  std::vector<double> x = out.optima.front().values;
  determine(fin, x, held, best, out);
  region(p, fin, x, held, out);
  describe(mf, x, held, best, out);
  return out;
}

}  // namespace metrosync
