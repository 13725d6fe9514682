// What `metrosync scale` prints: the scaled parameters of a rig (SPEC section 2), as the one JSON
// object of `--json` (also summary.json's "scaled") or as a table for people.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "models/rig.h"
#include "models/scaling.h"

namespace metrosync {

// {"epsilon", "law", "mu" (coulomb, none: 0, fixed: null) or "c" (viscous), per-metronome arrays
//  "nu", "J", "theta_c", "alpha", "zeta", "A_star" (null where J < J_c), "time_scale" (seconds
//  per unit of scaled time, 1/omega0)}
nlohmann::json scaleJson(const Rig& rig, const ScaledParams& p);

// The same as a readable table, with J_c and the physical values behind the scaled ones.
std::string scaleText(const Rig& rig, const ScaledParams& p);

}  // namespace metrosync
