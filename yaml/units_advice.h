// Internal to yaml/: what to write instead of a key of the other units (issue 37). A physical rig
// refuses `metronomes.1.start.phi` ("only with units: scaled"); the advice names the key of its
// own units that sets the same thing: metronomes.1.start.angle and metronomes.1.start.rate.
#pragma once

#include <string>

#include "models/rig.h"

namespace metrosync::rigfile {

// The advice for `key` under `parent` (as typed: "metronomes.1.start", "" at the top) in a rig of
// `rig_units`, e.g. "this rig is physical: set metronomes.1.start.angle (rad) and
// metronomes.1.start.rate (rad/s)"; "" when there is none.
std::string otherUnitsAdvice(const std::string& parent, const std::string& key, Units rig_units);

}  // namespace metrosync::rigfile
