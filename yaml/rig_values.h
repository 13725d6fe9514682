// Internal to yaml/: the build pass of a rig file: read, range-check and convert every value of a
// checked tree into a Rig (a scaled rig becomes its equivalent physical system).
#pragma once

#include <string>

#include "contact/friction_law.h"
#include "models/rig.h"
#include "yaml/rig_reader.h"

namespace metrosync::rigfile {

// platform_path and metronomes_path name the platform and its metronomes in messages: "platform"
// and "metronomes" in a single-platform rig, "platforms.I" and "platforms.I.metronomes" for a
// platform of a network (whose tree is given in the single-platform form, see buildNetworkRig).
Rig buildPhysical(const Node& root, const Source& src, const std::string& fallback_name,
                  const std::string& platform_path = "platform",
                  const std::string& metronomes_path = "metronomes");
Rig buildScaled(const Node& root, const Source& src, const std::string& fallback_name);

// platform.friction in either units (its parameters are scaled in a scaled rig): the law its
// name and keys choose (contact/law_registry.h), each parameter >= 0, the law's own rules.
FrictionLaw readFriction(const Reader& platform, Units units);

}  // namespace metrosync::rigfile
