#include "contact/friction_law.h"

namespace metrosync {

const char* toString(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::Coulomb:
      return "coulomb";
    case FrictionLaw::Viscous:
      return "viscous";
    case FrictionLaw::None:
      return "none";
    case FrictionLaw::Fixed:
      return "fixed";
  }
  return "?";
}

}  // namespace metrosync
