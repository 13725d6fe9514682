#include "contact/platform_friction.h"

namespace metrosync {

double PlatformFriction::lawForce(double v, PlatformMode mode) const {
  return law_ ? law_->force(constants_, v, mode) : 0.0;
}

double PlatformFriction::forceSlope(double v, PlatformMode mode) const {
  return law_ ? law_->forceSlope(constants_, v, mode) : 0.0;
}

LawGradient PlatformFriction::forceGradient(double v, PlatformMode mode) const {
  return law_ ? law_->forceGradient(constants_, v, mode) : LawGradient{};
}

LawGradient PlatformFriction::staticBoundGradient() const {
  return law_ && traits_.set_valued ? law_->staticBoundGradient(constants_) : LawGradient{};
}

}  // namespace metrosync
