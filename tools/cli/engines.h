// The two engines of the full model behind `--engine` (SPEC section 2): "simbody"
// (sim/engines/simbody/simbody_engine.h, a Simbody multibody system) and "direct" (sim/engines/direct/direct_engine.h,
// minimal coordinates). Both run every rig and agree (tests/direct/test_agreement.cpp); the
// direct one is two orders of magnitude faster, so it is the default, except when the rig's
// simulation.integrator names one of Simbody's integrators.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/record/run_report.h"

namespace metrosync::cli {

// The engine that runs `rig`'s full model: `requested` is "simbody", "direct" or "" (the default,
// as above). Throws UsageError for an unknown engine and RigError (prefixed by `rig_name`) when
// simulation.integrator is not one of that engine's integrators.
std::string chooseEngine(const std::string& requested, const Rig& rig, const std::string& rig_name);

// Runs the full model on `engine` (as returned by chooseEngine).
RunReport runFullModelOn(const std::string& engine, const Rig& rig, RunSink& sink);

// "simbody: rk-merson (default), ...; direct: verner65 (default), ..." for --help.
std::string integratorHelp();

}  // namespace metrosync::cli
