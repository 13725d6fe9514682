// CoulombLaw, the one rule both engines use for the platform's stick and slip.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "contact/coulomb.h"

namespace metrosync {
namespace {

TEST(CoulombLaw, HoldsStrictlyInsideTheBoundAndBreaksFreeAtIt) {
  const CoulombLaw law{2.0};
  const double below = std::nextafter(2.0, 0.0);
  EXPECT_FALSE(law.breaksFree(0.0));
  EXPECT_FALSE(law.breaksFree(below));
  EXPECT_FALSE(law.breaksFree(-below));
  EXPECT_TRUE(law.breaksFree(2.0));  // a tie breaks free (the located event has margin 0)
  EXPECT_TRUE(law.breaksFree(-2.0));
  EXPECT_TRUE(law.breaksFree(2.5));
  EXPECT_TRUE(law.breaksFree(std::numeric_limits<double>::quiet_NaN()));  // never "holds" NaN
}

TEST(CoulombLaw, SlipsAgainstTheNeededHoldingForce) {
  const CoulombLaw law{1.0};
  // friction would have to push +x to hold: the other forces push -x
  EXPECT_EQ(law.modeAtRest(1.5), PlatformMode::SlipNegative);
  EXPECT_EQ(law.modeAtRest(-1.5), PlatformMode::SlipPositive);
  EXPECT_EQ(law.modeAtRest(0.3), PlatformMode::Stuck);
  // the kinetic force opposes the slip
  EXPECT_EQ(law.slipForce(PlatformMode::SlipPositive), -1.0);
  EXPECT_EQ(law.slipForce(PlatformMode::SlipNegative), 1.0);
  EXPECT_EQ(law.slipForce(PlatformMode::Stuck), 0.0);
  EXPECT_DOUBLE_EQ(law.stickMargin(-0.25), 0.75);
}

}  // namespace
}  // namespace metrosync
