// The direct engine's one witness list (sim/events/witness_list.h) on a harmonic oscillator,
// theta'' = -theta, theta(0) = 0, theta'(0) = A (so theta = A sin t), one step of verner76 over
// its first maximum: which witnesses report, and where, against the closed form.
//   - a tick whose angle passes theta_c inside the step reports, bracketed around asin(theta_c /
//   A);
//   - a grazing tick (both ends of the step below theta_c, the maximum above) reports too;
//   - a disarmed side, a side the pre-filter rules out, a side the oscillation never reaches do
//   not;
//   - a contact with no linear form (stuck) is the run's: its own detection, its own value.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "sim/events/witness_list.h"
#include "sim/ode/rk_stepper.h"
#include "sim/ode/rk_tableau.h"

namespace metrosync {
namespace {

struct Oscillator : ode::OdeRhs {
  void eval(const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -y[0];
  }
};

// A run with one pendulum (angle in slot 0) and one platform whose contact is stuck.
struct ToyRun {
  double theta_c = 0.5;
  bool armed_plus = true;
  int stuck_detections = 0;
  bool armed(const RunWitness& w) const { return w.side < 0 || armed_plus; }
  std::optional<LinearForm> linearForm(const RunWitness& w) const {
    if (w.tick()) return LinearForm{0, -1, static_cast<double>(w.side), theta_c};
    return std::nullopt;
  }
  std::optional<WindowCrossing> detectStuck(int index, const RunWitness&) {
    ++stuck_detections;
    return WindowCrossing{index, {0.25, 0.75}};
  }
  double stuckValueAt(const RunWitness&, double th) { return th - 0.5; }
};

// One step over [t0, t1] of theta = A sin t.
struct Step {
  Oscillator f;
  ode::RkStepper s;
  double err = 0.0;
  Step(double amplitude, double t0, double t1) : s(ode::rkTableau("verner76"), 2, f) {
    const double y0[2] = {amplitude * std::sin(t0), amplitude * std::cos(t0)};
    s.setTolerances(1e-4, {1e-4, 1e-4});  // loose: the step is kept as it is, not retried
    s.restart(t0, y0);
    err = s.attempt(t1 - t0);
  }
};

WitnessList ticksAndContact() {
  WitnessList list;
  list.addTicks(0);    // witnesses 0 (+1) and 1 (-1)
  list.addContact(0);  // witness 2
  return list;
}

// The dense output of a step of length 0.4 is accurate to ~1e-9 here: the bracket holds the
// closed-form root within that much.
constexpr double kDense = 1e-8;

TEST(WitnessList, TickInsideTheStepIsBracketedAtTheClosedFormRoot) {
  const double t0 = 0.3, h = 0.4, A = 1.0;  // theta_c = 0.5 at t = asin(0.5) = 0.5236
  Step st(A, t0, t0 + h);
  ASSERT_LE(st.err, 1.0);
  ToyRun run;
  WitnessList list = ticksAndContact();
  ASSERT_TRUE(list.findCrossings(st.s, run, [](const RunWitness& w) { return w.tick(); }));
  ASSERT_EQ(list.found().size(), 1u);  // the contact was ruled out by the pre-filter
  EXPECT_EQ(run.stuck_detections, 0);
  const WindowCrossing c = list.found()[0];
  EXPECT_EQ(c.witness, 0);
  EXPECT_LT(list.valueAt(st.s, run, 0, c.th.lo), 0.0);
  EXPECT_GE(list.valueAt(st.s, run, 0, c.th.hi), 0.0);
  const double th_root = (std::asin(run.theta_c / A) - t0) / h;
  EXPECT_GT(th_root, 0.0);
  EXPECT_LT(th_root, 1.0);
  // locate it (sim/events/window.h) and compare with the closed form
  const double th_e =
      locateWindow(list.found(), [&](int w, double th) { return list.valueAt(st.s, run, w, th); });
  EXPECT_NEAR(th_e, th_root, kDense / h);
}

TEST(WitnessList, GrazingTickIsFoundAndADisarmedSideIsNot) {
  // theta = A sin t peaks at pi / 2; A just above theta_c: both ends of [1.2, 1.94] below theta_c
  const double A = 0.52, t0 = 1.2, t1 = 1.94;
  Step st(A, t0, t1);
  ASSERT_LE(st.err, 1.0);
  ToyRun run;
  ASSERT_LT(A * std::sin(t0), run.theta_c);
  ASSERT_LT(A * std::sin(t1), run.theta_c);
  WitnessList list = ticksAndContact();
  auto ticks_only = [](const RunWitness& w) { return w.tick(); };
  ASSERT_TRUE(list.findCrossings(st.s, run, ticks_only));
  ASSERT_EQ(list.found().size(), 1u);
  EXPECT_EQ(list.found()[0].witness, 0);  // the +theta_c side; -theta_c is never reached
  run.armed_plus = false;
  EXPECT_FALSE(list.findCrossings(st.s, run, ticks_only));
  EXPECT_TRUE(list.found().empty());
}

TEST(WitnessList, StuckContactIsTheRunsOwn) {
  Step st(0.1, 0.0, 0.4);  // no tick anywhere near
  ToyRun run;
  WitnessList list = ticksAndContact();
  ASSERT_TRUE(list.findCrossings(st.s, run, [](const RunWitness&) { return true; }));
  EXPECT_EQ(run.stuck_detections, 1);
  ASSERT_EQ(list.found().size(), 1u);
  EXPECT_EQ(list.found()[0].witness, 2);
  EXPECT_EQ(list.valueAt(st.s, run, 2, 0.75), 0.25);  // the run's stuckValueAt
  // the pre-filter skips it without asking the run
  EXPECT_FALSE(list.findCrossings(st.s, run, [](const RunWitness&) { return false; }));
  EXPECT_EQ(run.stuck_detections, 1);
}

}  // namespace
}  // namespace metrosync
