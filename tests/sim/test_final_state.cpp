// The final state at the requested end (SPEC 3 "final", docs/outputs.md), for both full-model
// engines: summary's final row is at tau_end, envelope.csv starts at tau = 0 with the start's
// envelope and ends with that final row, and the final row is the average over the last fast
// period ENDING at t_end, checked against an independent average of a dense trajectory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "base/constants.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "tests/simbody/rigs.h"

namespace metrosync {
namespace {

using Engine = std::function<RunReport(const Rig&, RunSink&)>;

struct EngineCase {
  std::string name;
  Engine run;
};

std::vector<EngineCase> engines() {
  return {{"direct", [](const Rig& r, RunSink& s) { return runDirectModel(r, s); }},
          {"simbody", [](const Rig& r, RunSink& s) { return runSimbody(networkOfOne(r), s); }}};
}

// The average of A_i = hypot(theta_i, thetadot_i) and of exp(i (atan2(theta_i, thetadot_i) - t))
// over [t_end - 2 pi, t_end] (or [0, t_end] if shorter), by the trapezoid rule on the trajectory
// rows (scaled units: t, x, xdot, theta_1, thetadot_1, theta_2, thetadot_2, platform), the first
// piece cut at t_end - 2 pi by linear interpolation.
struct Average {
  double A[2] = {0, 0};
  std::complex<double> e[2];
};

Average lastPeriodAverage(const std::vector<std::vector<double>>& traj) {
  const double t_end = traj.back()[0], t_from = std::max(traj.front()[0], t_end - kTwoPi);
  const double span = t_end - t_from;
  auto values = [](const std::vector<double>& row, int i, double& A, std::complex<double>& e) {
    const double th = row[3 + 2 * i], w = row[4 + 2 * i];
    A = std::hypot(th, w);
    e = std::complex<double>(w / A, th / A) * std::polar(1.0, -row[0]);
  };
  Average avg;
  for (size_t k = 1; k < traj.size(); ++k) {
    double ta = traj[k - 1][0];
    const double tb = traj[k][0];
    if (tb <= t_from) continue;
    for (int i = 0; i < 2; ++i) {
      double Aa, Ab;
      std::complex<double> ea, eb;
      values(traj[k - 1], i, Aa, ea);
      values(traj[k], i, Ab, eb);
      if (ta < t_from) {
        const double w = (t_from - ta) / (tb - ta);
        Aa += w * (Ab - Aa);
        ea += w * (eb - ea);
      }
      const double h = tb - std::max(ta, t_from);
      avg.A[i] += 0.5 * h * (Aa + Ab) / span;
      avg.e[i] += 0.5 * h * (ea + eb) / span;
    }
  }
  return avg;
}

// The paper's pair (mu = 0.3, escapement on) at epsilon = 0.1, ending 0.37 into a period: the
// amplitudes still grow (1.9 towards ~2.9), so the last period differs from the last grid row.
ScaledRigInput pair(double periods, double sample) {
  const double eps = 0.1;
  ScaledRigInput in = testrigs::scaledPair(eps, FrictionLaw::coulomb(0.3), 0.0, 0.4);
  in.tau_end = eps * kTwoPi * periods;
  in.sample = sample;
  in.accuracy = 1e-10;
  return in;
}

TEST(FinalState, FullModelFinalIsTheLastPeriodEndingAtTauEnd) {
  // a dense trajectory (6400 rows per period) for the independent average; the recorder samples
  // 64 per period plus both sides of every tick. Both are trapezoid rules: the independent one
  // smears each tick's jump over one row (first order in the row spacing), the recorder's is
  // exact at the jumps but has the O(h^2) error of 64 samples per period. Measured differences,
  // the same for both engines: 1.6e-4 (400 rows per period), 5.3e-5 (1600), 3.3e-5 (6400),
  // 2.0e-5 (25600): 1e-4 is 3x the difference at 6400 rows, and the last period row differs
  // from the final row by > 1e-2.
  constexpr double kQuadratureTol = 1e-4;
  const ScaledRigInput in = pair(7.37, kTwoPi / 6400);
  const Rig rig = rigFromScaled(in);
  for (const EngineCase& engine : engines()) {
    MemorySink sink;
    const RunReport rep = engine.run(rig, sink);
    ASSERT_TRUE(rep.complete) << engine.name << ": " << rep.failure;
    const auto& env = sink.envelope;
    ASSERT_EQ(env.size(), 1u + 7u + 1u) << engine.name;  // start, 7 periods, final
    // final.tau is the requested tau (to rounding), and the envelope's last row is the final row
    EXPECT_NEAR(rep.final_row.tau, in.tau_end, 1e-12 * in.tau_end) << engine.name;
    EXPECT_EQ(env.back().tau, rep.final_row.tau) << engine.name;
    EXPECT_EQ(env.back().A, rep.final_row.A) << engine.name;
    // the first row is the start's envelope: A = 1.9 for both, psi = 0.4 (phases 0.4 and 0)
    EXPECT_EQ(env.front().tau, 0.0) << engine.name;
    EXPECT_NEAR(env.front().A[0], 1.9, 1e-12) << engine.name;
    EXPECT_NEAR(env.front().A[1], 1.9, 1e-12) << engine.name;
    EXPECT_NEAR(env.front().psi[0], 0.4, 1e-12) << engine.name;
    // the final row against the independent average of the dense trajectory
    const Average avg = lastPeriodAverage(sink.trajectory);
    EXPECT_NEAR(sink.trajectory.back()[0], in.tau_end / in.epsilon, 1e-9) << engine.name;
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(rep.final_row.A[i], avg.A[i], kQuadratureTol) << engine.name << " A_" << i + 1;
    const double psi = std::arg(avg.e[0]) - std::arg(avg.e[1]);
    EXPECT_NEAR(std::remainder(rep.final_row.psi[0] - psi, kTwoPi), 0.0, kQuadratureTol)
        << engine.name;
    // the last grid row (the period before) is measurably different: the check can fail
    const EnvelopeRow& last_period = env[env.size() - 2];
    EXPECT_GT(std::fabs(last_period.A[0] - avg.A[0]), 100 * kQuadratureTol) << engine.name;
    double worst = std::fabs(std::remainder(rep.final_row.psi[0] - psi, kTwoPi));
    for (int i = 0; i < 2; ++i) worst = std::max(worst, std::fabs(rep.final_row.A[i] - avg.A[i]));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3e", worst);
    RecordProperty(engine.name + "_final_vs_independent", buf);
  }
}

TEST(FinalState, FullModelShorterThanAPeriodAveragesWhatThereIs) {
  // half a period: the final row averages [0, t_end], checked against the dense trajectory's
  // average over the same span (tolerance as above)
  constexpr double kQuadratureTol = 1e-4;
  const ScaledRigInput in = pair(0.5, kTwoPi / 6400);
  const Rig rig = rigFromScaled(in);
  for (const EngineCase& engine : engines()) {
    MemorySink sink;
    const RunReport rep = engine.run(rig, sink);
    ASSERT_TRUE(rep.complete) << engine.name << ": " << rep.failure;
    ASSERT_EQ(sink.envelope.size(), 2u) << engine.name;  // the start and the final row
    EXPECT_NEAR(rep.final_row.tau, in.tau_end, 1e-12 * in.tau_end) << engine.name;
    const Average avg = lastPeriodAverage(sink.trajectory);
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(rep.final_row.A[i], avg.A[i], kQuadratureTol) << engine.name << " A_" << i + 1;
    const double psi = std::arg(avg.e[0]) - std::arg(avg.e[1]);
    EXPECT_NEAR(std::remainder(rep.final_row.psi[0] - psi, kTwoPi), 0.0, kQuadratureTol)
        << engine.name;
  }
}

}  // namespace
}  // namespace metrosync
