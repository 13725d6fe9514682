// One metronome on a platform held still: the shooting orbit against a long run of the engine.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/engines/direct/direct_engine.h"
#include "sim/record/run_report.h"
#include "tests/periodic_orbit/fixtures.h"

namespace metrosync::orbit {
namespace {

using testing::finalState;
using testing::singleFixed;

TEST(SingleMetronome, ShootingOrbitIsWhereALongRunEnds) {
  const Rig rig = singleFixed(1.9, 100.0);  // tau 100: ~220 periods, contraction ~0.8 each
  const ReturnMap map(rig, 0);
  ASSERT_EQ(map.section().dim(), 1);  // thetadot_1 on theta_1 = 0
  // Newton from a rough guess, far from the orbit
  std::string why;
  const auto orbit = shoot(map, Vec::Constant(1, 1.9), 2 * M_PI, {}, &why);
  ASSERT_TRUE(orbit) << why;
  EXPECT_LE(orbit->residual, 1e-10);
  // the long run's end, put on the section
  const Vec z = finalState(rig, map.model(), 1e-12);
  const Pass settled = map.firstCrossing(z, 3 * 2 * M_PI);
  EXPECT_NEAR(settled.u1(0), orbit->u(0), 1e-9);
  EXPECT_LT(orbit->pass.mismatch, 1e-9);
  std::printf("u* = %.15g, period %.15g, multiplier %.12g, iterations %d, residual %.3g\n",
              orbit->u(0), orbit->period, orbit->multipliers(0).real(), orbit->iterations,
              orbit->residual);
}

}  // namespace
}  // namespace metrosync::orbit

namespace metrosync::orbit {
namespace {

// The ticks at +theta_c (rising) of one long run: a section of its own. Its state there
// approaches the orbit's geometrically, by the nontrivial multiplier each period.
struct TickSink : RunSink {
  std::vector<double> rates;  // thetadot just before each tick at +theta_c
  bool wantsEventRows() const override { return false; }
  bool wantsEventRecords() const override { return true; }
  void eventRecord(const char*, int, const std::vector<double>& before,
                   const std::vector<double>&) override {
    if (before[3] > 0) rates.push_back(before[4]);
  }
};

TEST(SingleMetronome, MultiplierIsTheLongRunsContraction) {
  const Rig rig = testing::singleFixed(1.9, 100.0);
  const ReturnMap map(rig, 0);
  const auto orbit = shoot(map, Vec::Constant(1, 2.0), 2 * M_PI);
  ASSERT_TRUE(orbit);
  Rig r = rig;
  r.sim.accuracy = 1e-12;
  TickSink ticks;
  ASSERT_TRUE(runDirectModel(r, ticks).complete);
  ASSERT_GT(ticks.rates.size(), 100u);
  const double limit = ticks.rates.back();
  // ratios of successive deviations while they are small (linear: the next order is ~1e-5 of
  // the ratio) and large against the run's own noise (~1e-12)
  std::vector<double> ratios;
  for (size_t k = 0; k + 1 < ticks.rates.size(); ++k) {
    const double d0 = ticks.rates[k] - limit, d1 = ticks.rates[k + 1] - limit;
    if (std::abs(d0) < 1e-5 && std::abs(d1) > 1e-7) ratios.push_back(d1 / d0);
  }
  ASSERT_GE(ratios.size(), 5u);
  const double mu = orbit->multipliers(0).real();
  for (double q : ratios) EXPECT_NEAR(q, mu, 1e-4) << "measured contraction per period";
  std::printf("multiplier %.10f, measured %.10f .. %.10f (%zu ratios)\n", mu, ratios.front(),
              ratios.back(), ratios.size());
}

}  // namespace
}  // namespace metrosync::orbit
