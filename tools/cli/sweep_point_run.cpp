#include "tools/cli/sweep_point_run.h"

#include <cmath>
#include <limits>

#include "base/number_text.h"
#include "sim/analysis/network_verdict.h"
#include "sim/analysis/regime.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/fault_hooks.h"
#include "tools/cli/network_sweep.h"
#include "tools/cli/sweep_summary.h"
#include "tools/report/outputs.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

// The model --model asks for: as given, else the --engine's, else the slow flow.
std::string requestedModel(const SweepOptions& opt) {
  if (!opt.model.empty()) return opt.model;
  return opt.engine.empty() ? "slow" : "";
}

// Is the rig text a network of platforms? Decided once per thread for the text it last saw: every
// point of a sweep (and every basin sample) has the same text, and parsing it once more per point
// cost 1.5% of a slow-flow point (docs/bench/sweep-throughput.md). --set and --vary cannot make a
// text a network: only the text's own `platforms` key does (yaml/network_loader.h).
bool isNetworkRig(const std::string& text) {
  thread_local std::string last_text;
  thread_local bool known = false, last = false;
  if (!known || text != last_text) {
    last = isNetworkText(text);
    last_text = text;
    known = true;
  }
  return last;
}

}  // namespace

std::string sweepRigText(const SweepOptions& opt) {
  // the same checks as every command: a regular file of bounded size (yaml/rig_loader.h)
  if (opt.rig_text) return *opt.rig_text;
  return opt.rig_path.empty() ? defaultRigYaml() : readRigFile(opt.rig_path);
}

std::string displayName(const SweepOptions& opt) {
  return opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
}

// The rig of one point: the base rig, --set, then the point's KEY=VALUE (a wildcard key
// "metronomes.*.REST" set at each of the n metronomes); checked like `run` checks its rig.
// `where` names the point ("grid point 12 (...)"); throws RigError naming it.
PointInput loadPointRig(const std::string& text, const SweepOptions& opt,
                        const std::vector<std::string>& point, const std::string& where,
                        const std::string& source) {
  std::vector<std::string> overrides = opt.sets;
  overrides.insert(overrides.end(), point.begin(), point.end());
  PointInput in;
  try {
    if (isNetworkRig(text))
      in.net = loadPlatformsNetwork(text, displayName(opt), overrides, engineLoadOptions(HUGE_VAL));
    in.rig = in.net ? networkSweepRig(*in.net) : loadRigText(text, displayName(opt), overrides);
  } catch (const RigError& e) {
    // the loader calls every override --set; the point's own ones come from --vary
    std::string what = e.what();
    for (const auto& o : point)
      for (size_t at = what.find("--set " + o); at != std::string::npos;
           at = what.find("--set " + o, at))
        what.replace(at, 6 + o.size(), source + " " + o);
    throw RigError(what + "\n  at " + where);
  }
  if (in.net) {  // docs/networks.md
    in.engine = &chooseEngine(opt.engine, opt.model, *in.net, displayName(opt), "sweeps");
    return in;
  }
  // checks --engine against --model and the point's integrator
  in.engine = &chooseEngine(opt.engine, requestedModel(opt), in.rig, displayName(opt));
  try {
    in.scaled = computeScaled(in.rig);
  } catch (const std::invalid_argument& e) {
    throw RigError(displayName(opt) + ": " + e.what() + "\n  at " + where);
  }
  return in;
}

PointInput loadPoint(const std::string& text, const SweepOptions& opt, const SweepGrid& grid,
                     long g) {
  const std::vector<std::string> point = grid.overrides(g);
  return loadPointRig(text, opt, point,
                      "grid point " + std::to_string(g) + " (" + joined(point) + ") of the sweep");
}

std::optional<SweepPoint> runPoint(const PointInput& in, long g, bool keep) {
  PointHooks hooks;
  hooks.stop = &FileSink::stopRequested;  // SIGINT, SIGTERM (tools/cli/stop_signals.h)
  hooks.fault = &injectedFailure;         // tests (tools/cli/fault_hooks.h)
  hooks.keep_envelope = keep;
  return metrosync::runPoint(in, g, hooks);
}

std::pair<std::string, std::string> checkSweepPoint(const std::string& rig_text,
                                                    const SweepOptions& opt,
                                                    const std::vector<std::string>& point, int n,
                                                    const std::string& where) {
  const PointInput in = loadPointRig(rig_text, opt, point, where, "the drawn");
  if (static_cast<int>(in.rig.metronomes.size()) != n)
    throw UsageError(joined(point) + " changes the number of metronomes (at " + where + ")");
  return {in.engine->model(), in.engine->name()};
}

std::optional<SweepPoint> runSweepPointAt(const std::string& rig_text, const SweepOptions& opt,
                                          const std::vector<std::string>& point, int n,
                                          long index) {
  std::optional<PointInput> in;
  try {
    in = loadPointRig(rig_text, opt, point, "point " + std::to_string(index));
  } catch (const std::exception& e) {
    return unloadablePoint(index, n, e.what());
  }
  if (static_cast<int>(in->rig.metronomes.size()) != n)
    return unloadablePoint(index, n, "the point changes the number of metronomes");
  return runPoint(*in, index, false);  // basin samples: no envelope kept
}

}  // namespace metrosync::cli
