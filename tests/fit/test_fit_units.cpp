// The pieces of fit's verdict against closed forms: the noise level estimated from a record's
// high-frequency part (sim/analysis/fit/noise_level.h) against the noise put in, and the standard
// errors and identifiability rule (sim/analysis/fit/fit_statistics.h) on a linear model, where
// sigma^2 (J^T J)^-1 is exact; and the likelihood region's interval (likelihood_region.h)
// against a scan of a two-valley cost.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <sstream>

#include "sim/analysis/fit/data_file.h"
#include "sim/analysis/fit/fit_statistics.h"
#include "sim/analysis/fit/least_squares.h"
#include "sim/analysis/fit/likelihood_region.h"
#include "sim/analysis/fit/noise_level.h"
#include "tests/fit/fit_data.h"

namespace metrosync {
namespace {

using namespace fit_testing;

// The pair's angles (6 s of the direct engine) every `stride` x 10 ms with N(0, sigma) noise.
MeasuredData pairRecord(double sigma, int stride, unsigned seed) {
  Rig rig = loadRigText(kPairRig, "pair.yaml");
  rig.sim.sample_s = kSampleS;
  MemorySink sink;
  EXPECT_TRUE(findEngine("direct")->run(rig, sink).complete);
  std::mt19937 gen(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::ostringstream os;
  os.precision(15);
  os << "t,theta_1,theta_2\n";
  for (std::size_t k = 0; k < sink.trajectory.size(); k += stride) {
    const std::vector<double>& row = sink.trajectory[k];
    os << row[0] << "," << row[3] + noise(gen) << "," << row[5] + noise(gen) << "\n";
  }
  return parseDataText(os.str(), "pair.csv", 2);
}

const std::vector<double> kThetaC = {0.244, 0.244};

// At 100 Hz (30 samples a period) the estimate is the noise put in, from 1e-4 to 1e-2 rad,
// whatever the escapement's ticks do to the signal.
TEST(NoiseLevel, IsTheNoisePutInAt100Hz) {
  for (const double sigma : {1e-4, 1e-3, 1e-2}) {
    SCOPED_TRACE(sigma);
    const MeasuredData d = pairRecord(sigma, 1, 3);
    const std::vector<bool> ticks = escapementTicks(d, kThetaC);
    for (const DataColumn& c : d.columns) {
      const NoiseEstimate e = estimateNoise(d, c, ticks);
      EXPECT_NEAR(e.sigma, sigma, 0.1 * sigma) << c.name;
      EXPECT_TRUE(e.reliable) << c.name;
    }
  }
}

// At 33 Hz (10 samples a period) a swing is no quartic over 7 samples: with 1e-4 rad of noise the
// estimate is the signal's, and it says so (not reliable: an upper bound).
TEST(NoiseLevel, SaysWhenTheSignalFillsTheWindows) {
  const MeasuredData d = pairRecord(1e-4, 3, 4);
  const std::vector<bool> ticks = escapementTicks(d, kThetaC);
  const NoiseEstimate e = estimateNoise(d, d.columns[0], ticks);
  EXPECT_GT(e.sigma, 2e-4);
  EXPECT_FALSE(e.reliable);
}

// Without the escapement's ticks skipped, the kinks they leave in theta (a jump of the rate) fill
// many windows: the estimate skips them, and would be 2.5 times too large at 1e-4 rad otherwise.
TEST(NoiseLevel, SkipsTheEscapementsTicks) {
  const MeasuredData d = pairRecord(1e-4, 1, 5);
  const std::vector<bool> none(d.t_s.size(), false);
  EXPECT_GT(estimateNoise(d, d.columns[0], none).sigma, 1.5e-4);
  EXPECT_NEAR(estimateNoise(d, d.columns[0], escapementTicks(d, kThetaC)).sigma, 1e-4, 1e-5);
}

FreeParameter key(const std::string& name, double scale) {
  FreeParameter p;
  p.name = name;
  p.start = scale;
  p.scale = scale;
  p.lower = 0.0;
  return p;
}

// r = A v - y for a fixed A (3 keys, 200 observations, N(0, 1) noise): J, the standard errors
// and the correlations are sigma^2 (A^T A)^-1 exactly; a key whose value is below its standard
// error is the least determined, and columns that are one the same key twice are collinear.
TEST(FitStatistics, LinearModelErrorsAndTheIdentifiabilityRule) {
  const int m = 200;
  std::mt19937 gen(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  Eigen::MatrixXd A(m, 3);
  Eigen::VectorXd e(m);
  for (int i = 0; i < m; ++i) {
    const double t = i / double(m);
    A.row(i) << 1.0, t, std::sin(7 * t);
    e(i) = noise(gen);
  }
  const std::vector<double> v = {2.0, 3.0, 0.01};  // the third is within its error of 0
  const std::vector<FreeParameter> free = {key("a", 1.0), key("b", 1.0), key("c", 1.0)};
  const ResidualFunction f = [&](const std::vector<double>& x, double* r) {
    Eigen::Map<Eigen::VectorXd>(r, m) =
        A * Eigen::Vector3d(x[0], x[1], x[2]) - A * Eigen::Vector3d(v[0], v[1], v[2]) - e;
    return true;
  };
  const Linearization lin = linearize(f, m, v, free);
  EXPECT_EQ(lin.smooth_rows, m);
  EXPECT_LT((lin.J - A).norm(), 1e-8 * A.norm());
  const Uncertainty u = uncertainty(lin, v, free, {false, false, false});
  const Eigen::Matrix3d cov = e.squaredNorm() / (m - 3) * (A.transpose() * A).inverse();
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(*u.std_errors[j], std::sqrt(cov(j, j)), 1e-9 * std::sqrt(cov(j, j)));
    EXPECT_NEAR(*u.correlation[0][j], cov(0, j) / std::sqrt(cov(0, 0) * cov(j, j)), 1e-9);
  }
  EXPECT_GT(*u.std_errors[2], v[2]);
  EXPECT_EQ(u.worst, 2);
  // held, the other two are determined
  EXPECT_EQ(uncertainty(lin, v, free, {false, false, true}).worst, -1);
  // two keys that act alike: collinear
  Linearization twice = lin;
  twice.J.col(1) = 2 * twice.J.col(0);
  const Uncertainty c = uncertainty(twice, v, free, {false, false, true});
  EXPECT_GE(c.worst, 0);
  EXPECT_NE(c.why.find("combination"), std::string::npos) << c.why;
}

// A key the record determines to 1e-9 of itself, as a long record's late phase does (docs/bench/
// fit.md, seed 2's record 7): r_i = sin(phi_i(x)) - sin(phi_i(1)) - e_i, phi_i = 2 pi t_i (10 +
// 1e4 (x - 1)), t_i in [0, 1), N(0, 1e-3) noise. A difference over 1e-4 of x turns the late
// phases by up to 2 pi: a secant across a wrapped phase, not the derivative.
struct WrappingPhase {
  static constexpr int m = 2000;
  static constexpr double kSigma = 1e-3, kRate = 1e4;
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(m, 0.0, 1.0 - 1.0 / m), e{m};
  WrappingPhase() {
    std::mt19937 gen(7);
    std::normal_distribution<double> noise(0.0, kSigma);
    for (int i = 0; i < m; ++i) e(i) = noise(gen);
  }
  Eigen::VectorXd phase(double x) const { return 2 * M_PI * t.array() * (10 + kRate * (x - 1)); }
  bool operator()(const std::vector<double>& x, double* r) const {
    Eigen::Map<Eigen::VectorXd>(r, m) =
        phase(x[0]).array().sin() - phase(1.0).array().sin() - e.array();
    return true;
  }
  // the derivative in closed form
  Eigen::VectorXd column(double x) const {
    return (phase(x).array().cos() * (2 * M_PI * kRate) * t.array()).matrix();
  }
};

// The Jacobian is the derivative (to 1e-4), and the standard error sigma / |J| (to 1e-3): the
// difference step shrinks where the model stops being linear over it (difference_step.h).
TEST(FitStatistics, DifferenceStepStaysWhereTheModelIsLinear) {
  const WrappingPhase model;
  const std::vector<double> v = {1.0};
  const std::vector<FreeParameter> free = {key("x", 1.0)};
  const Linearization lin = linearize(std::cref(model), model.m, v, free);
  const Eigen::VectorXd exact = model.column(1.0);
  EXPECT_LT((lin.J.col(0) - exact).norm(), 1e-4 * exact.norm());
  EXPECT_EQ(lin.smooth_rows, model.m);
  const Uncertainty u = uncertainty(lin, v, free, {false});
  const double se = std::sqrt(model.e.squaredNorm() / (model.m - 1)) / exact.norm();
  EXPECT_NEAR(*u.std_errors[0], se, 1e-3 * se);
}

// The local solver reaches the least-squares minimum of that key (to a quarter of its standard
// error: the solver stops at a change of 1e-8 of the key) from 300 standard errors off
// (a turn of 0.02 rad of the last phase): its derivatives take the same step rule. The minimum:
// Gauss-Newton with the closed-form derivative.
TEST(FitStatistics, SolverConvergesOnAKeyDeterminedToOnePartIn1e9) {
  const WrappingPhase model;
  double best = 1.0;
  for (int k = 0; k < 20; ++k) {
    Eigen::VectorXd r(model.m);
    model({best}, r.data());
    const Eigen::VectorXd J = model.column(best);
    best -= J.dot(r) / J.squaredNorm();
  }
  const double se = model.kSigma / model.column(best).norm();
  LocalProblem p;
  p.residuals = std::cref(model);
  p.residual_count = model.m;
  p.start = {best + 300 * se};
  p.scale = {1.0};
  p.lower = {0.0};
  p.held = {false};
  const LocalSolution s = solveLocal(p);
  EXPECT_NEAR(s.values[0], best, 0.25 * se) << s.report;
}

// The likelihood region's interval (likelihood_region.h) against a brute-force scan of the
// sublevel set of a cost with two valleys of the same curvature (one key, standard error se):
// chi2(v) = min((v - a)^2, (v - b)^2 + rise) / se^2, the second valley `rise` variances above
// the first. The region {v: chi2 - min chi2 < 9} is the interval's, the standard error its
// farther side from a over 3; a valley at or above 9 variances adds nothing; with the best alone
// the interval is a -+ 3 se and the standard error se exactly (no inflation).
TEST(LikelihoodRegion, IsTheSublevelSetOfATwoValleyCost) {
  const double a = 1.0, se = 0.01;
  const auto scan = [&](double b, double rise) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (double v = a - 0.2; v <= a + 0.2; v += 1e-6) {
      const double chi2 = std::min((v - a) * (v - a), (v - b) * (v - b) + rise * se * se);
      if (chi2 / (se * se) < 9) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    return std::make_pair(lo, hi);
  };
  for (const auto& [b, rise] : std::vector<std::pair<double, double>>{
           {a + 0.025, 2.0}, {a - 0.033, 4.4}, {a + 0.05, 0.5}, {a + 0.04, 8.0}}) {
    SCOPED_TRACE(b);
    const auto iv = likelihoodIntervals({a}, {se}, {{{b}, rise}}, {-HUGE_VAL});
    ASSERT_TRUE(iv[0]);
    const auto [lo, hi] = scan(b, rise);
    EXPECT_NEAR(iv[0]->lower, lo, 2e-6);
    EXPECT_NEAR(iv[0]->upper, hi, 2e-6);
    EXPECT_TRUE(iv[0]->from_optima);
    EXPECT_NEAR(iv[0]->std_error, std::max(a - lo, hi - a) / 3, 1e-6);
    EXPECT_GT(iv[0]->std_error, se);
  }
  // a valley 9 or more variances up is outside the region; the best alone: no inflation
  for (const std::vector<RegionOptimum>& others :
       {std::vector<RegionOptimum>{}, std::vector<RegionOptimum>{{{a + 0.05}, 9.0}}}) {
    const auto iv = likelihoodIntervals({a}, {se}, others, {-HUGE_VAL});
    EXPECT_EQ(iv[0]->std_error, se);
    EXPECT_FALSE(iv[0]->from_optima);
    EXPECT_NEAR(iv[0]->lower, a - 3 * se, 1e-15);
    EXPECT_NEAR(iv[0]->upper, a + 3 * se, 1e-15);
  }
  // a key without a standard error has no interval; a bound cuts the interval, not the error
  const auto iv = likelihoodIntervals({a, 0.02}, {std::nullopt, se}, {}, {0.0, 0.0});
  EXPECT_FALSE(iv[0]);
  EXPECT_EQ(iv[1]->lower, 0.0);
  EXPECT_EQ(iv[1]->std_error, se);
}

}  // namespace
}  // namespace metrosync
