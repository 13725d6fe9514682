// The registry of sim/engines/engine.h: the three engines as thin adapters over their entry
// points (runDirect, runSimbody, runSlowFlow), whose internals live in
// their folders; runSimbody through the Simbody plugin (sim/engines/simbody_plugin.h).
#include <algorithm>
#include <stdexcept>

#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/engine.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "sim/engines/simbody_plugin.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"

namespace metrosync {

namespace {

// The slow flow's absolute error target as a fraction of simulation.accuracy (its relative
// target): the envelope's amplitudes are O(1) and its phases O(pi), so 1e-2 keeps the absolute
// test from ruling where a component passes through 0 without making it the binding one elsewhere.
constexpr double kSlowFlowAtolPerRtol = 1e-2;

class DirectEngine final : public Engine {
 public:
  std::string name() const override { return "direct"; }
  std::string model() const override { return "full"; }
  std::vector<std::string> integrators() const override { return directIntegratorNames(); }
  std::string defaultIntegrator(const Rig& rig) const override {
    return defaultDirectIntegrator(rig);
  }
  std::string description() const override {
    return "the full model in minimal coordinates (the default; ~100x faster than simbody)";
  }
  // the one model of the rig's kind whatever the sink wants (a single board's states too:
  // rig_recorder.h), so that the same board runs the same arithmetic in every command
  RunReport run(const Network& net, RunSink& sink) const override { return runDirect(net, sink); }
  bool runsNetworks() const override { return true; }
};

class SimbodyEngine final : public Engine {
 public:
  std::string name() const override { return "simbody"; }
  std::string model() const override { return "full"; }
  std::vector<std::string> integrators() const override { return simbodyIntegratorNames(); }
  std::string defaultIntegrator(const Rig&) const override {
    return simbodyIntegratorNames().front();
  }
  std::string description() const override {
    return "the full model as a Simbody multibody system (the default when "
           "simulation.integrator names a Simbody integrator)";
  }
  // Simbody itself is in a plugin (sim/engines/simbody_plugin.h), loaded when selected
  void load() const override { simbodyPlugin(); }
  RunReport run(const Network& net, RunSink& sink) const override {
    return simbodyPlugin().run(net, sink);
  }
  bool runsNetworks() const override { return true; }
};

class SlowFlowEngine final : public Engine {
 public:
  std::string name() const override { return "slowflow"; }
  std::string model() const override { return "slow"; }
  std::vector<std::string> integrators() const override { return {}; }
  std::string defaultIntegrator(const Rig&) const override { return ""; }
  std::string description() const override {
    return "the slow flow (the averaged envelope equations), to the rig's tau";
  }
  RunReport run(const Network& net, RunSink& sink) const override {
    if (!net.isSingleRig())
      throw std::logic_error("the slowflow engine runs single-platform rigs only");
    const Rig rig = net.toSingleRig();
    if (const std::string key = rig.fullModelOnlyKey(); !key.empty())
      throw std::invalid_argument(key + ": the air's drag has no averaged form in the slow flow");
    const ScaledParams sp = computeScaled(rig);
    SlowFlowOptions so;
    so.tau_end = sp.tau_end;
    // simulation.accuracy is the relative local error target of whichever integrator runs
    so.rtol = rig.sim.accuracy;
    so.atol = kSlowFlowAtolPerRtol * rig.sim.accuracy;
    return runSlowFlow(sp, so, sink);
  }
};

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string listed(const std::vector<std::string>& v, const std::string& first_note) {
  std::string s;
  for (size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + v[k] + (k == 0 ? first_note : "");
  return s;
}

// The engine whose integrator `integrator` is, or nullptr.
const Engine* ownerOf(const std::string& integrator) {
  for (const Engine* e : engines())
    if (contains(e->integrators(), integrator)) return e;
  return nullptr;
}

const Engine& byName(const std::string& requested) {
  const Engine* e = findEngine(requested);
  if (!e)
    throw EngineSelectionError(
        "--engine " + requested + ": unknown engine (one of: " + engineNames() + ")", false);
  return *e;
}

// The engine when none is requested: the slow flow for the slow model; for the full model the
// direct engine, or Simbody when the rig names one of its integrators.
const Engine& defaultEngine(const std::string& model, const std::string& integrator) {
  if (model == "slow") return byName("slowflow");
  const Engine* owner = ownerOf(integrator);
  return owner && owner->model() == "full" ? *owner : byName("direct");
}

// An engine with no integrators of its own (the slow flow) accepts any known name: the key is
// then the full model's, so that one rig serves `run --model slow` and `compare`.
void checkIntegrator(const Engine& e, const std::string& integrator) {
  if (integrator.empty() || contains(e.integrators(), integrator)) return;
  const Engine* owner = ownerOf(integrator);
  const std::string head = "simulation.integrator = " + integrator + ": ";
  if (!owner)
    throw EngineSelectionError(head + "unknown integrator; one of: " + integratorHelp(), true);
  if (e.integrators().empty()) return;
  throw EngineSelectionError(head + "an integrator of the " + owner->name() +
                                 " engine, for --engine " + owner->name() + " only; the " +
                                 e.name() + " engine's are " + listed(e.integrators(), ""),
                             true);
}

}  // namespace

const std::vector<const Engine*>& engines() {
  static const DirectEngine direct;
  static const SimbodyEngine simbody;
  static const SlowFlowEngine slowflow;
  static const std::vector<const Engine*> all = {&direct, &simbody, &slowflow};
  return all;
}

const Engine* findEngine(const std::string& name) {
  for (const Engine* e : engines())
    if (e->name() == name) return e;
  return nullptr;
}

const Engine& selectEngine(const std::string& requested, const std::string& model,
                           const std::string& integrator) {
  if (!model.empty() && model != "full" && model != "slow")
    throw EngineSelectionError("--model " + model + ": must be full or slow", false);
  const Engine& e = !requested.empty() ? byName(requested)
                                       : defaultEngine(model.empty() ? "full" : model, integrator);
  if (!model.empty() && e.model() != model)
    throw EngineSelectionError("--engine " + e.name() + " runs the " + e.model() +
                                   " model, not --model " + model + " (the " + model +
                                   " model's engines: " + engineNames(model) + ")",
                               false);
  checkIntegrator(e, integrator);
  e.load();
  return e;
}

std::string integratorHelp() {
  std::string s;
  for (const Engine* e : engines()) {
    if (e->integrators().empty()) continue;
    s += (s.empty() ? "" : "; ") + e->name() + " engine: " + listed(e->integrators(), "");
    s += e->name() == "direct" ? " (default: verner76, or dopri5 for more than 8 swinging "
                                 "metronomes)"
                               : " (default: " + e->integrators().front() + ")";
  }
  return s;
}

std::string engineNames(const std::string& model) {
  std::string s;
  for (const Engine* e : engines())
    if (model.empty() || e->model() == model) s += (s.empty() ? "" : ", ") + e->name();
  return s;
}

}  // namespace metrosync
