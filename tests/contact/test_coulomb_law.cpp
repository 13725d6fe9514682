// SetValuedLaw, the one rule both engines use for the platform's stick and slip; the escapement
// rule; the platform's law as both engines query it. Property tests over many random inputs and
// at the exact ties (|holding| == bound, xdot == 0 exactly, |theta| == theta_c).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "contact/escapement.h"
#include "contact/friction_law.h"
#include "contact/law_registry.h"
#include "contact/platform_friction.h"
#include "contact/set_valued_law.h"

namespace metrosync {
namespace {

constexpr int kTrials = 20000;

TEST(SetValuedLaw, HoldsStrictlyInsideTheBoundAndBreaksFreeAtIt) {
  const SetValuedLaw law = SetValuedLaw::coulomb(2.0);
  const double below = std::nextafter(2.0, 0.0);
  EXPECT_FALSE(law.breaksFree(0.0));
  EXPECT_FALSE(law.breaksFree(below));
  EXPECT_FALSE(law.breaksFree(-below));
  EXPECT_TRUE(law.breaksFree(2.0));  // a tie breaks free (the located event has margin 0)
  EXPECT_TRUE(law.breaksFree(-2.0));
  EXPECT_TRUE(law.breaksFree(2.5));
  EXPECT_TRUE(law.breaksFree(std::numeric_limits<double>::quiet_NaN()));  // never "holds" NaN
}

TEST(SetValuedLaw, SlipsAgainstTheNeededHoldingForce) {
  const SetValuedLaw law = SetValuedLaw::coulomb(1.0);
  // friction would have to push +x to hold: the other forces push -x
  EXPECT_EQ(law.modeAtRest(1.5), PlatformMode::SlipNegative);
  EXPECT_EQ(law.modeAtRest(-1.5), PlatformMode::SlipPositive);
  EXPECT_EQ(law.modeAtRest(0.3), PlatformMode::Stuck);
  // Coulomb's slip force opposes the slip, whatever its speed; none while stuck
  const PlatformFriction f = FrictionLaw::coulomb(1.0).platform(1.0);
  EXPECT_EQ(f.force(0.3, PlatformMode::SlipPositive), -1.0);
  EXPECT_EQ(f.force(-7.0, PlatformMode::SlipNegative), 1.0);
  EXPECT_EQ(f.force(0.0, PlatformMode::Stuck), 0.0);
  EXPECT_DOUBLE_EQ(law.stickMargin(-0.25), 0.75);
}

// The decisions must be one rule: whatever the input, canHold, breaksFree, modeAtRest and the
// sign of the stick margin say the same thing, and a slip from rest goes the way the other forces
// push (against the holding force).
void expectConsistent(const SetValuedLaw& law, double h) {
  const bool hold = law.canHold(h);
  EXPECT_EQ(hold, !law.breaksFree(h)) << "h " << h << " bound " << law.staticBound();
  EXPECT_EQ(hold, law.modeAtRest(h) == PlatformMode::Stuck) << "h " << h;
  EXPECT_EQ(hold, law.stickMargin(h) > 0) << "h " << h << " bound " << law.staticBound();
  if (!hold) {
    EXPECT_LE(static_cast<int>(law.modeAtRest(h)) * h, 0.0) << "h " << h;
  }
  // at xdot == 0 exactly the mode is the mode at rest; any velocity slips its own way
  EXPECT_EQ(law.modeAt(0.0, h), law.modeAtRest(h));
  EXPECT_EQ(law.modeAt(-0.0, h), law.modeAtRest(h));
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(law.modeAt(tiny, h), PlatformMode::SlipPositive);
  EXPECT_EQ(law.modeAt(-tiny, h), PlatformMode::SlipNegative);
}

TEST(SetValuedLaw, OneRuleOverRandomInputs) {
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> mag(-3.0, 3.0), exp10(-12.0, 12.0);
  for (int k = 0; k < kTrials; ++k) {
    const SetValuedLaw law = SetValuedLaw::coulomb(std::pow(10.0, exp10(rng)));
    expectConsistent(law, mag(rng) * law.staticBound());
    expectConsistent(law, std::pow(10.0, exp10(rng)) * (k % 2 ? 1 : -1));
  }
}

TEST(SetValuedLaw, OneRuleAtTheExactTies) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exp10(-12.0, 12.0);
  for (int k = 0; k < kTrials; ++k) {
    const SetValuedLaw law = SetValuedLaw::coulomb(std::pow(10.0, exp10(rng)));
    for (double h : {law.staticBound(), -law.staticBound()}) {
      expectConsistent(law, h);
      EXPECT_FALSE(law.canHold(h)) << "a tie breaks free";
      EXPECT_EQ(law.stickMargin(h), 0.0);
      EXPECT_EQ(law.modeAtRest(h), SetValuedLaw::slipDirection(h));
      // one ulp inside holds
      const double inside = std::nextafter(h, 0.0);
      expectConsistent(law, inside);
      EXPECT_TRUE(law.canHold(inside));
    }
  }
  // a zero bound (mu = 0) holds nothing, not even a zero force
  expectConsistent(SetValuedLaw::coulomb(0.0), 0.0);
  EXPECT_FALSE(SetValuedLaw::coulomb(0.0).canHold(0.0));
}

TEST(SetValuedLaw, BoundIsTheCoefficientTimesTheNormalForce) {
  const SetValuedLaw law = FrictionLaw::coulomb(0.25).platform(8.0).bounds();
  EXPECT_DOUBLE_EQ(law.staticBound(), 2.0);
  EXPECT_DOUBLE_EQ(law.kineticBound(), 2.0);
}

TEST(Escapement, DueExactlyFromTheSlackOutwards) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> tc_dist(0.01, 1.5), rate(-5.0, 5.0), frac(0.0, 2.0);
  for (int k = 0; k < kTrials; ++k) {
    const Escapement e{tc_dist(rng), 1.0};
    const double th = frac(rng) * e.theta_c * (k % 2 ? 1 : -1), w = rate(rng);
    const bool outward = th * w > 0;
    const bool past = std::abs(th) >= e.theta_c * (1 - Escapement::kSlack);
    EXPECT_EQ(e.due(th, w), outward && past);
    // a due side is never re-armed (a tick cannot be both consumed and armed)
    if (e.due(th, w)) {
      EXPECT_FALSE(e.rearms(th, Escapement::side(th)));
    }
    // the witness rises through zero at theta_c on its side
    EXPECT_EQ(e.witness(th, Escapement::side(th)) >= 0, std::abs(th) >= e.theta_c);
    EXPECT_EQ(e.tickImpulse(th), Escapement::side(th) * e.impulse);
  }
  const Escapement e{0.9, 2.8};
  EXPECT_TRUE(e.due(0.9, 1e-300));  // the tie: exactly at theta_c, moving outwards
  EXPECT_FALSE(e.due(0.9, 0.0));    // at rest at theta_c: no outward rate
  EXPECT_FALSE(e.due(-0.9, 1.0));   // inwards
  EXPECT_TRUE(e.due(-0.9, -1.0));
  EXPECT_TRUE(e.due(0.9 * (1 - Escapement::kSlack), 1.0));
  EXPECT_FALSE(e.due(std::nextafter(0.9 * (1 - Escapement::kSlack), 0.0), 1.0));
  EXPECT_FALSE((Escapement{0.9, 0.0}.due(1.0, 1.0)));  // no escapement
}

// Every registered law: dissipative, no force while stuck, set-valued exactly when a moving
// platform is held by a small push (holdsDrive), its force at the constant-slip fast path equal
// to its own function's.
TEST(PlatformFriction, EveryLawDissipatesAndTheSetValuedOnesHold) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> v_dist(-10.0, 10.0), c_dist(0.0, 5.0);
  for (const LawKind* kind : lawRegistry()) {
    std::vector<double> values;
    for (std::size_t k = 0; k < kind->parameters().size(); ++k) values.push_back(c_dist(rng));
    std::sort(values.begin(), values.end());  // mu_static >= mu
    const FrictionLaw law(*kind, values);
    const double N = c_dist(rng);
    const PlatformFriction f = law.platform(N);
    const double small = values.empty() ? 1e-9 : 1e-9 * values.front();
    EXPECT_EQ(f.setValued(), f.platformMoves() && law.holdsDrive(small)) << law.name();
    const LawConstants k{f.constants().values, N};
    for (int i = 0; i < 1000; ++i) {
      const double v = v_dist(rng);
      const PlatformMode m = v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
      EXPECT_GE(f.power(v, m), 0.0) << law.name();
      EXPECT_EQ(f.power(v, m), -f.force(v, m) * v);
      EXPECT_EQ(f.force(v, m), law.kind().force(k, v, m)) << law.name();
    }
    EXPECT_EQ(f.force(0.0, PlatformMode::Stuck), 0.0) << law.name();
  }
  const PlatformFriction viscous = FrictionLaw::viscous(0.5).platform(1.0);
  EXPECT_DOUBLE_EQ(viscous.force(2.0, PlatformMode::Stuck), -1.0);
}

}  // namespace
}  // namespace metrosync
