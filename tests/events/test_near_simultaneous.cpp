// Near-simultaneous crossings on both engines (issue 10, the lost tick): identical metronomes
// whose theta_c crossings are separated by delta in {0, 1e-16, ..., 1e-8}, in phase and in
// antiphase, started by phases and by theta/thetadot.
//   - every metronome gets the same number of ticks (a lost tick breaks the symmetry at once);
//   - the engines agree on the final state to 1e-8 in scaled units (direct at accuracy 1e-12,
//     Simbody at 1e-14: tests/direct/test_agreement.cpp says why; measured agreement ~1e-10);
//   - the final state is continuous in delta: delta = 0 against 1e-12 within 1e-6 (a tick moved
//     by 1e-12 moves the state by O(1e-12); a tick lost or doubled moves it by O(eps J) ~ 0.1);
//   - exact antiphase given by phases keeps the platform stuck, |x| < 1e-9 throughout.
// The runs are 1.5 units of slow time (3 fast periods, 6 ticks per metronome): long enough for
// several pairs of ticks, short enough for the whole suite to take seconds.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <ostream>
#include <string>
#include <tuple>

#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "tests/events/near_simultaneous.h"

namespace metrosync {
namespace {

using eventtests::pairRig;
using eventtests::Start;

constexpr double kTau = 1.5;
// engines' agreement in scaled units (see the file's comment)
constexpr double kAgree = 1e-8;
// continuity in delta: 1e-12 apart (see the file's comment)
constexpr double kContinuity = 1e-6;
// a stuck platform's position: exactly 0 unless a tick is lost (then O(0.1))
constexpr double kStuck = 1e-9;

struct Case {
  Start start;
  bool antiphase;
  double delta;
};

struct Runs {
  RunReport direct, simbody;
  MemorySink direct_sink, simbody_sink;
};

const Runs& runsFor(const Case& c) {
  static std::map<std::tuple<int, bool, double>, Runs> cache;
  const auto key = std::make_tuple(static_cast<int>(c.start), c.antiphase, c.delta);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Runs& r = cache[key];
  Rig rig = pairRig(c.start, c.antiphase, c.delta, kTau);
  r.direct = runDirectModel(rig, r.direct_sink);
  rig.sim.accuracy = 1e-14;
  r.simbody = runSimbody(networkOfOne(rig), r.simbody_sink);
  return r;
}

std::string describe(const Case& c) {
  return std::string(c.start == Start::ByPhase ? "by phase" : "by state") +
         (c.antiphase ? ", antiphase" : ", in phase") + ", delta " + eventtests::num(c.delta);
}

// gtest prints the parameter with this (instead of its bytes)
void PrintTo(const Case& c, std::ostream* os) {
  *os << describe(c);
}

class NearSimultaneous : public ::testing::TestWithParam<Case> {};

TEST_P(NearSimultaneous, EqualTicksAndTheEnginesAgree) {
  const Case c = GetParam();
  const Runs& r = runsFor(c);
  ASSERT_TRUE(r.direct.complete) << r.direct.failure;
  ASSERT_TRUE(r.simbody.complete) << r.simbody.failure;
  for (const RunReport* rep : {&r.direct, &r.simbody}) {
    ASSERT_EQ(rep->counts.escapements.size(), 2u);
    EXPECT_GE(rep->counts.escapements[0], 4) << rep->engine;
    EXPECT_EQ(rep->counts.escapements[0], rep->counts.escapements[1])
        << rep->engine << ", " << describe(c);
  }
  EXPECT_EQ(r.direct.counts.escapements, r.simbody.counts.escapements) << describe(c);
  const auto& a = r.direct.final_trajectory_row;
  const auto& b = r.simbody.final_trajectory_row;
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 1; k + 1 < a.size(); ++k)
    EXPECT_NEAR(a[k], b[k], kAgree) << describe(c) << ": column " << k;
  EXPECT_EQ(a.back(), b.back()) << describe(c) << ": platform mode";
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (Start s : {Start::ByPhase, Start::ByState})
    for (bool anti : {true, false})
      for (double d : {0.0, 1e-16, 1e-14, 1e-12, 1e-10, 1e-8}) cases.push_back({s, anti, d});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Deltas, NearSimultaneous, ::testing::ValuesIn(allCases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           const Case& c = info.param;
                           std::string d = c.delta == 0 ? "0"
                                                        : std::to_string(static_cast<int>(
                                                              std::round(-std::log10(c.delta))));
                           return std::string(c.start == Start::ByPhase ? "Phase" : "State") +
                                  (c.antiphase ? "Anti" : "In") + "_delta1em" + d;
                         });

TEST(NearSimultaneous, FinalStateIsContinuousInDelta) {
  for (Start s : {Start::ByPhase, Start::ByState})
    for (bool anti : {true, false}) {
      const Runs& r0 = runsFor({s, anti, 0.0});
      const Runs& r12 = runsFor({s, anti, 1e-12});
      for (int e = 0; e < 2; ++e) {
        const auto& a = e ? r0.simbody.final_trajectory_row : r0.direct.final_trajectory_row;
        const auto& b = e ? r12.simbody.final_trajectory_row : r12.direct.final_trajectory_row;
        ASSERT_EQ(a.size(), b.size());
        for (size_t k = 1; k + 1 < a.size(); ++k)
          EXPECT_NEAR(a[k], b[k], kContinuity)
              << (e ? "simbody" : "direct") << ", " << describe({s, anti, 0.0}) << ": column " << k;
      }
    }
}

TEST(NearSimultaneous, ExactAntiphaseByPhasesKeepsThePlatformStuck) {
  const Runs& r = runsFor({Start::ByPhase, true, 0.0});
  for (const MemorySink* sink : {&r.direct_sink, &r.simbody_sink}) {
    ASSERT_FALSE(sink->trajectory.empty());
    double x_max = 0.0;
    for (const auto& row : sink->trajectory) x_max = std::max(x_max, std::abs(row[1]));
    EXPECT_LT(x_max, kStuck);
  }
  EXPECT_EQ(r.direct.counts.stick_slip, 0);
  EXPECT_EQ(r.simbody.counts.stick_slip, 0);
}

}  // namespace
}  // namespace metrosync
