// The engines behind one interface (docs/engines.md): each has a name, the model it runs, its
// integrators and `run(rig, sink)`. The registry (engine_registry.cpp) holds the three engines
// of this build -- "direct" and "simbody" run the full model (e1.1a-c), "slowflow" the slow
// flow -- and is the only place that maps a name to an engine: the commands choose an engine with
// selectEngine() and run it through this interface, never by comparing names.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "models/network.h"
#include "models/rig.h"
#include "sim/record/run_report.h"

namespace metrosync {

class Engine {
 public:
  virtual ~Engine() = default;
  virtual std::string name() const = 0;   // "direct", "simbody", "slowflow"
  virtual std::string model() const = 0;  // "full" or "slow"
  // Names accepted by simulation.integrator with this engine; empty when the engine has one
  // fixed integrator and ignores the key (the slow flow).
  virtual std::vector<std::string> integrators() const = 0;
  // The integrator used when simulation.integrator is empty ("" for the slow flow).
  virtual std::string defaultIntegrator(const Rig& rig) const = 0;
  // One line for --help: what the engine is and when to choose it.
  virtual std::string description() const = 0;
  // Loads what the engine needs that the executable does not link (the simbody engine's plugin,
  // sim/engines/plugin_loader.h); throws PluginError when it cannot. selectEngine() calls it, so
  // that a missing plugin is reported before anything is written.
  virtual void load() const {}
  // Runs the network to its end (net.sim.t_end_s; a single rig's tau for the slow flow) into
  // `sink` (sim/record/run_report.h: a single rig's rows, a network's states). A single rig is
  // the network of one, networkOfOne(rig) (run(rig, sink) below); a single rig's run writes its
  // rows exactly as it always has. As the engines' own entry points: a failed simulation gives
  // complete = false; RunInterrupted and SimulationFailure thrown by the sink pass through. An
  // engine that does not runsNetworks() throws std::logic_error for a network that is not a
  // single rig (Network::isSingleRig).
  virtual RunReport run(const Network& net, RunSink& sink) const = 0;
  RunReport run(const Rig& rig, RunSink& sink) const { return run(networkOfOne(rig), sink); }
  // Does the engine run networks of two or more platforms (docs/networks.md)?
  virtual bool runsNetworks() const { return false; }
};

// Every engine of this build, in the order --help lists them (the default full engine first).
const std::vector<const Engine*>& engines();

// The engine called `name`, or nullptr.
const Engine* findEngine(const std::string& name);

// A command line or rig that names an engine, model and integrator that do not go together.
// `about_integrator`: the rig's simulation.integrator is at fault (a rig error), else the
// command line (--engine / --model).
struct EngineSelectionError : std::invalid_argument {
  EngineSelectionError(const std::string& what, bool about_integrator)
      : std::invalid_argument(what), about_integrator(about_integrator) {}
  bool about_integrator;
};

// The engine that runs `model` ("full", "slow", or "" = the requested engine's model, else full)
// with `requested` ("" = the model's default: for the full model the direct engine, unless
// `integrator` names a Simbody integrator) and the rig's simulation.integrator `integrator`
// ("" = the engine's default). Throws EngineSelectionError for an unknown engine or integrator,
// an engine of the other model, or an integrator of another engine; PluginError (from
// Engine::load) when the engine's plugin cannot be loaded.
const Engine& selectEngine(const std::string& requested, const std::string& model,
                           const std::string& integrator);

// "direct: verner76 (default), ...; simbody: rk-merson (default), ..." for --help.
std::string integratorHelp();

// "direct, simbody, slowflow" (or only the engines of `model` when given).
std::string engineNames(const std::string& model = "");

}  // namespace metrosync
