#include "yaml/rig_plan.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "yaml/rig_limits.h"
#include "yaml/rig_reader.h"
#include "yaml/spelling.h"

namespace metrosync::rigfile {

namespace {

// What a run of the rig would write, against the caller's limit (yaml/rig_limits.h); blamed on
// simulation.sample if given, else on the run's length.
void checkOutput(const Reader& sim, const char* duration_key, const Rig& rig,
                 const LoadOptions& opt) {
  const char* culprit = sim.has("sample") ? "sample" : duration_key;
  if (!std::isfinite(rig.sim.t_end_s))
    sim.bad(duration_key, "the run would end at t = " + numberText(rig.sim.t_end_s) +
                              " s: it must end at a finite time");
  if (rig.sim.sample_s > 0 && rig.sim.sample_s < rig.sim.t_end_s * kSampleResolution)
    sim.bad("sample", "below the time resolution of the run (" + numberText(kSampleResolution) +
                          " * its length, " + numberText(rig.sim.t_end_s * kSampleResolution) +
                          " s here): consecutive rows would have the same time");
  const OutputEstimate e = estimateOutput(rig);
  if (e.periods > kMaxRunPeriods)  // every command: the cost of the run itself (issue 29)
    sim.bad(duration_key,
            "the run would span " + numberText(e.periods) + " fast periods" +
                (rig.units == Units::Scaled ? " (the fast time runs to tau / epsilon)" : "") +
                ", above the limit of " + numberText(kMaxRunPeriods) +
                " for any command (docs/rig-limits.md): shorten the run");
  if (!(e.bytes > opt.max_output_bytes)) return;
  sim.bad(culprit, "the run would write about " + numberText(e.trajectory_rows) +
                       " trajectory rows (every " + numberText(e.sample_s) + " s) and " +
                       numberText(e.envelope_rows) + " envelope rows, about " +
                       numberText(e.bytes) + " bytes, above the output limit of " +
                       numberText(opt.max_output_bytes) +
                       " bytes: raise simulation.sample, shorten the run, or lift the limit with "
                       "--max-output BYTES");
}

// Where a start is blamed: the --set that changed one of its values if any, else the start map.
Where startCulprit(const Reader& metronome) {
  const Node* start = metronome.find("start");
  if (!start) return metronome.at();
  for (const Entry& e : start->map)
    if (e.value.at.origin > 0) return e.value.at;
  return start->at;
}

}  // namespace

void checkPlan(const Node& root, const Rig& rig, const Source& src, const LoadOptions& opt) {
  const Reader top(root, "", src);
  const Reader sim = top.map("simulation", "");
  const char* duration_key = rig.units == Units::Physical ? "duration" : "tau";
  if (auto name = sim.optText("integrator"); name && !opt.integrators.empty()) {
    const auto& names = opt.integrators;
    if (std::find(names.begin(), names.end(), *name) == names.end()) {
      std::string why = "unknown integrator";
      if (auto c = closest(*name, names)) why += " (did you mean '" + *c + "'?)";
      sim.bad("integrator", why + "; " + opt.integrator_help);
    }
  }
  checkOutput(sim, duration_key, rig, opt);
  const Node& list = *top.find("metronomes");
  for (std::size_t i = 0; i < rig.metronomes.size() && i < list.seq.size(); ++i) {
    const std::optional<std::string> why = overTheTop(rig.metronomes[i], rig.gravity_m_s2);
    if (!why) continue;
    const Reader m(list.seq[i], "metronomes." + std::to_string(i), src);
    src.fail(startCulprit(m), m.path("start") + ": " + *why);
  }
}

}  // namespace metrosync::rigfile
