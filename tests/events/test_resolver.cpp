// The event resolver (sim/events/resolver.h) on a tiny fake engine: a platform and two pendulums
// with a constant mass matrix [[M, c1, c2], [c1, I, 0], [c2, 0, I]] and a holding force the test
// sets. Checks the order (ticks, then the platform), that the order of the pendulums does not
// matter, exact momentum, the plastic stop, the consumed tick and the counts.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "contact/friction_law.h"
#include "contact/law_registry.h"
#include "sim/events/resolver.h"

namespace metrosync {
namespace {

struct FakeSystem : EventSystem {
  double M = 3.0, I = 0.5;
  Eigen::Vector2d c{0.4, 0.4};
  Eigen::Vector2d th{0.0, 0.0}, w{0.0, 0.0};
  double v = 0.0, holding = 0.0;
  PlatformMode m = PlatformMode::Stuck;
  std::vector<std::string> rows;
  int impulses = 0;

  Eigen::Matrix3d mass() const {
    Eigen::Matrix3d A;
    A << M, c(0), c(1), c(0), I, 0, c(1), 0, I;
    return A;
  }
  Eigen::Vector3d u() const { return {v, w(0), w(1)}; }
  double momentum() const { return mass().row(0).dot(u()); }

  double theta(int j) const override { return th(j); }
  double thetadot(int j) const override { return w(j); }
  double xdot() const override { return v; }
  PlatformMode mode() const override { return m; }
  void setMode(PlatformMode to) override {
    m = to;
    if (to == PlatformMode::Stuck) v = 0.0;
  }
  double holdingForce() override { return holding; }
  double applyImpulse(const std::vector<double>& pin, double px) override {
    ++impulses;
    const Eigen::Vector3d p(px, pin[0], pin[1]);
    const Eigen::Vector3d du = mass().ldlt().solve(p);
    const double dT = p.dot(u() + 0.5 * du);
    v += du(0);
    w += du.tail<2>();
    return dT;
  }
  double platformMobility() override { return mass().inverse()(0, 0); }
  void eventRow(const char* kind) override { rows.emplace_back(kind); }
};

const PlatformFriction kLaw = FrictionLaw::coulomb(0.2).platform(1.0);
constexpr double kPeriod = 6.283185307179586;
constexpr double kThetaC = 0.9;

EventResolver makeResolver(const FakeSystem& s) {
  return EventResolver({{kThetaC, 0.1}, {kThetaC, 0.1}}, kLaw, kPeriod,
                       {s.th(0) * 0.5, s.th(1) * 0.5});  // armed: inside at the start
}

// Exact antiphase: the two ticks cancel on the platform exactly, as ONE impulse.
TEST(EventResolver, CancellingTicksAreOneImpulseAndKeepThePlatformStuck) {
  FakeSystem s;
  s.th << kThetaC, -kThetaC;
  s.w << 1.9, -1.9;
  EventResolver r = makeResolver(s);
  const double p0 = s.momentum();
  const WindowOutcome out = r.resolve(s, false);
  EXPECT_EQ(out.ticked.size(), 2u);
  EXPECT_EQ(s.impulses, 1);
  EXPECT_EQ(s.v, 0.0);
  EXPECT_EQ(s.m, PlatformMode::Stuck);
  EXPECT_EQ(out.stick_slip, 0);
  EXPECT_EQ(out.plastic_stops, 0);
  EXPECT_EQ(s.momentum(), p0);
  EXPECT_EQ(s.rows, std::vector<std::string>{"tick"});
}

// A pendulum still inside its slack (crossing 1e-12 later) joins the window; the other side of
// the same pendulum, and a pendulum 1e-6 short of theta_c, do not.
TEST(EventResolver, EveryDueTickJoinsTheWindowWhateverReported) {
  FakeSystem s;
  s.th << kThetaC * (1 + 1e-15), -kThetaC * (1 - 1e-12);
  s.w << 1.9, -1.9;
  EventResolver r = makeResolver(s);
  EXPECT_EQ(r.resolve(s, false).ticked, (std::vector<int>{0, 1}));
  FakeSystem t;
  t.th << kThetaC, -kThetaC * (1 - 1e-6);
  t.w << 1.9, -1.9;
  EventResolver r2 = makeResolver(t);
  EXPECT_EQ(r2.resolve(t, false).ticked, (std::vector<int>{0}));
}

// A consumed tick does not fire again when its witness then crosses zero; it is re-armed once the
// pendulum is back inside theta_c (a rule on the state, not on time).
TEST(EventResolver, ATickIsConsumedUntilThePendulumIsBackInside) {
  FakeSystem s;
  s.th << kThetaC * (1 - 1e-12), 0.0;
  s.w << 1.9, 0.0;
  EventResolver r = makeResolver(s);
  EXPECT_EQ(r.resolve(s, false).ticked.size(), 1u);
  EXPECT_FALSE(r.armed(0, 1));
  s.th(0) = kThetaC * (1 + 1e-9);  // its witness crosses now
  s.setMode(PlatformMode::Stuck);
  EXPECT_TRUE(r.resolve(s, false).ticked.empty());
  r.rearm(s);
  EXPECT_FALSE(r.armed(0, 1));
  s.th(0) = 0.5 * kThetaC;  // back inside
  r.rearm(s);
  EXPECT_TRUE(r.armed(0, 1));
}

// The order of the pendulums does not matter: swapping them gives the same state, bit for bit.
TEST(EventResolver, TheOrderOfThePendulumsDoesNotMatter) {
  FakeSystem a;
  a.c << 0.4, 0.3;
  a.th << kThetaC, kThetaC * (1 + 1e-14);
  a.w << 1.9, 1.2;
  FakeSystem b = a;
  b.c << a.c(1), a.c(0);
  b.th << a.th(1), a.th(0);
  b.w << a.w(1), a.w(0);
  EventResolver ra = makeResolver(a), rb = makeResolver(b);
  const WindowOutcome oa = ra.resolve(a, false), ob = rb.resolve(b, false);
  EXPECT_EQ(oa.ticked.size(), 2u);
  EXPECT_NEAR(a.v, b.v, 1e-15 * std::abs(a.v));
  EXPECT_NEAR(a.w(0), b.w(1), 1e-15);
  EXPECT_NEAR(a.w(1), b.w(0), 1e-15);
  EXPECT_EQ(a.m, b.m);
  EXPECT_EQ(a.rows, b.rows);
}

// Ticks first, then the platform: a tick that sets the stuck platform moving is a slip in the
// direction of its velocity, decided after the impulse (not from the holding force before it).
TEST(EventResolver, TicksThenThePlatform) {
  FakeSystem s;
  s.th << kThetaC, 0.0;
  s.w << 1.9, 0.0;
  s.holding = -5.0;  // would break free towards +x if the platform rule came first
  EventResolver r = makeResolver(s);
  const WindowOutcome out = r.resolve(s, true);
  EXPECT_LT(s.v, 0.0);  // the tick on +theta_c pushes the platform towards -x (c > 0)
  EXPECT_EQ(s.m, PlatformMode::SlipNegative);
  EXPECT_EQ(out.stick_slip, 1);
  EXPECT_EQ(s.rows, (std::vector<std::string>{"slip", "tick"}));
}

// Nearly cancelling ticks: the residual velocity is a slip friction stops at once; the stop is
// friction's impulse on x alone (momentum changes by exactly that impulse, the pendulums take the
// reaction), and a stuck platform that stays stuck has not switched.
TEST(EventResolver, NearlyCancellingTicksEndInAPlasticStopWithItsReaction) {
  FakeSystem s;
  s.c << 0.4, 0.4 * (1 + 1e-12);
  s.th << kThetaC, -kThetaC;
  s.w << 1.9, -1.9;
  EventResolver r = makeResolver(s);
  FakeSystem after_ticks = s;
  after_ticks.applyImpulse({0.1, -0.1}, 0.0);
  ASSERT_NE(after_ticks.v, 0.0);
  const double p_ticks = after_ticks.momentum();
  const WindowOutcome out = r.resolve(s, false);
  EXPECT_EQ(out.plastic_stops, 1);
  EXPECT_EQ(out.stick_slip, 0);
  EXPECT_EQ(s.m, PlatformMode::Stuck);
  EXPECT_EQ(s.v, 0.0);
  // friction's impulse -v / (M^-1)_xx on x alone: the momentum after it
  const double p_expected = p_ticks - after_ticks.v / after_ticks.platformMobility();
  EXPECT_NEAR(s.momentum(), p_expected, 1e-15);
  // the pendulums took the reaction: their rates differ from the ticks' alone
  EXPECT_NE(s.w(0), after_ticks.w(0));
  EXPECT_GE(out.friction_out, 0.0);
}

// A platform stuck at the tie |H| == bound breaks free; a slip whose velocity reaches zero with a
// push beyond the bound the other way reverses (counted apart from stick <-> slip).
TEST(EventResolver, TheTieBreaksFreeAndReversalsAreCountedApart) {
  FakeSystem s;
  s.holding = kLaw.bounds().staticBound();
  EventResolver r = makeResolver(s);
  WindowOutcome out = r.resolve(s, true);
  EXPECT_EQ(s.m, PlatformMode::SlipNegative);
  EXPECT_EQ(out.stick_slip, 1);
  s.v = 1e-13;  // the slip's velocity has just passed zero (window end)
  s.holding = -2 * kLaw.bounds().staticBound();
  out = r.resolve(s, true);
  EXPECT_EQ(s.m, PlatformMode::SlipPositive);
  EXPECT_EQ(out.stick_slip, 0);
  EXPECT_EQ(out.slip_reversals, 1);
  EXPECT_EQ(s.v, 0.0);
}

// Static friction above kinetic (mu_static = 0.3 > mu = 0.2): a stuck platform holds every push
// below the static bound, even above the kinetic one; a slip that stops under such a push sticks,
// where Coulomb's law (one bound, 0.2) would slip again, the other way.
TEST(EventResolver, StaticFrictionHoldsBetweenTheKineticAndTheStaticBound) {
  const PlatformFriction stiction = FrictionLaw(staticCoulombLaw(), {0.2, 0.3}).platform(1.0);
  FakeSystem s;
  s.holding = 0.25;  // between the bounds
  EventResolver r({{kThetaC, 0.1}, {kThetaC, 0.1}}, stiction, kPeriod, {0.0, 0.0});
  WindowOutcome out = r.resolve(s, true);
  EXPECT_EQ(s.m, PlatformMode::Stuck);
  EXPECT_EQ(out.stick_slip, 0);
  s.holding = 0.3;  // the static bound itself breaks free (the tie)
  out = r.resolve(s, true);
  EXPECT_EQ(s.m, PlatformMode::SlipNegative);
  EXPECT_EQ(out.stick_slip, 1);
  s.v = 1e-13;  // the slip has just passed zero (window end); the push is between the bounds
  s.holding = -0.25;
  out = r.resolve(s, true);
  EXPECT_EQ(s.m, PlatformMode::Stuck) << "static friction holds it";
  EXPECT_EQ(s.v, 0.0);
  // the same with Coulomb's law at the kinetic bound: the stop turns into a slip the other way
  FakeSystem c;
  c.m = PlatformMode::SlipNegative;
  c.v = 1e-13;
  c.holding = -0.25;
  EventResolver coulomb({{kThetaC, 0.1}, {kThetaC, 0.1}}, kLaw, kPeriod, {0.0, 0.0});
  coulomb.resolve(c, true);
  EXPECT_EQ(c.m, PlatformMode::SlipPositive);
  // the slip force sets the micro-slip rule: friction decelerates at 0.2 * (M^-1)_xx
  EXPECT_EQ(stiction.force(1e-13, PlatformMode::SlipPositive), -0.2);
}

}  // namespace
}  // namespace metrosync
