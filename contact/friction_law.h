// Which law acts between the platform and the table: the names a rig file gives
// (platform.friction.law) and the mode of a platform under dry friction.
#pragma once

namespace metrosync {

enum class FrictionLaw { Coulomb, Viscous, None, Fixed };

const char* toString(FrictionLaw law);

// The platform's state under Coulomb friction: stuck, or sliding in one direction.
enum class PlatformMode : int { SlipNegative = -1, Stuck = 0, SlipPositive = 1 };

}  // namespace metrosync
