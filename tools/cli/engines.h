// `--engine` and `--model` on the command line: the registry's choice (sim/engines/engine.h)
// with its errors turned into the command line's (UsageError) or the rig's (RigError), both
// exit 2 before anything is written.
#pragma once

#include <string>

#include "models/network.h"
#include "models/rig.h"
#include "sim/engines/engine.h"
#include "yaml/load_options.h"

namespace metrosync::cli {

// The engine that runs `model` ("full", "slow", or "" = the engine's own) of `rig` with
// `requested` ("" = the default: see selectEngine). Throws UsageError for an unknown engine or
// one of the other model, RigError (prefixed by `rig_name`) when simulation.integrator is not
// one of that engine's integrators, or when the slow flow is chosen for a law without an averaged
// response (requireSlowFlow).
const Engine& chooseEngine(const std::string& requested, const std::string& model, const Rig& rig,
                           const std::string& rig_name);

// The same for what the loader returns, a rig or a network (yaml/network_loader.h): a single rig
// (Network::isSingleRig) as above; a network of several platforms the full model's engine
// (--engine, else the one simulation.integrator names, else direct), --model slow and an engine
// that runs no networks UsageError (exit 2); `verb` ("runs", "sweeps", "animates") says what the
// command does with the network.
const Engine& chooseEngine(const std::string& requested, const std::string& model,
                           const Network& net, const std::string& rig_name,
                           const std::string& verb);

// The loader's options of a command that runs a rig: every engine's integrator names
// (simulation.integrator is checked where it is written) and the output limit.
LoadOptions engineLoadOptions(double max_output_bytes);

// The slow flow needs the averaged response of the rig's friction law (contact/law_kind.h):
// throws RigError (exit 2), prefixed by `rig_name`, for a law that has none (static friction above
// kinetic).
void requireSlowFlow(const Rig& rig, const std::string& rig_name);
// RigError (exit 2) for a rig the full model's derivatives cannot take (Rig::fullModelOnlyKey:
// air drag): `continue --model full` and `fit`.
void requireDerivatives(const Rig& rig, const std::string& rig_name, const std::string& command);

// The --engine help of the commands that run the full model only (compare, validate, sweep's
// full model, bench) and of those that run either (run, sweep).
std::string fullEngineHelp();
std::string anyEngineHelp();

}  // namespace metrosync::cli
