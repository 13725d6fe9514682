#include "sim/analysis/periodic_orbit/engine_trace.h"

#include <algorithm>
#include <cstring>

#include "sim/engines/direct/direct_engine.h"
#include "sim/record/run_report.h"

namespace metrosync::orbit {

namespace {

// Keeps the event records only (no trajectory, no envelope, no event rows).
struct RecordSink : FinalStateSink {
  std::vector<EventRecord> records;
  bool wantsEventRecords() const override { return true; }
  void eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                   const std::vector<double>& after) override {
    records.push_back({kind, metronome, before, after});
  }
};

// The platform column of a row: the mode for a Coulomb platform (0 stuck, +-1 sliding).
PlatformMode modeOf(const std::vector<double>& row) {
  const double p = row.back();
  return p > 0 ? PlatformMode::SlipPositive
               : (p < 0 ? PlatformMode::SlipNegative : PlatformMode::Stuck);
}

template <class Model>
int swingingIndex(const Model& m, int rig_index) {
  for (int j = 0; j < m.n(); ++j)
    if (m.rigIndex(j) == rig_index) return j;
  return -1;
}

// The records of one window share its time: the first's state before, the last's after.
template <class Model>
std::vector<EngineWindow> windowsOf(const Model& m, const std::vector<EventRecord>& recs) {
  std::vector<EngineWindow> out;
  for (size_t k = 0; k < recs.size();) {
    const double t_row = recs[k].before[0];
    EngineWindow w;
    w.t = m.timeFromRow(recs[k].before);
    w.before = m.stateFromRow(recs[k].before);
    w.mode_before = modeOf(recs[k].before);
    size_t last = k;
    for (; last < recs.size() && recs[last].before[0] == t_row; ++last) {
      const EventRecord& r = recs[last];
      if (r.kind == "tick")
        w.ticked.push_back(swingingIndex(m, r.metronome));
      else
        w.platform_switch = true;
    }
    w.after = m.stateFromRow(recs[last - 1].after);
    w.mode_after = modeOf(recs[last - 1].after);
    std::sort(w.ticked.begin(), w.ticked.end());
    out.push_back(std::move(w));
    k = last;
  }
  return out;
}

// The windows at t > 0; those at t <= 0 without a tick are the engine's settling at the start: a
// platform that breaks free at once.
template <class Model>
EngineTrace traceOf(const Model& m, const std::vector<EventRecord>& records, double v0) {
  EngineTrace trace;
  trace.start_mode = v0 > 0 ? PlatformMode::SlipPositive
                            : (v0 < 0 ? PlatformMode::SlipNegative : PlatformMode::Stuck);
  for (EngineWindow& w : windowsOf(m, records)) {
    if (w.t <= 0 && w.ticked.empty()) {
      trace.start_mode = w.mode_after;
      continue;
    }
    trace.windows.push_back(std::move(w));
  }
  return trace;
}

}  // namespace

EngineTrace traceOfRecords(const ScaledModel& model, const std::vector<EventRecord>& records,
                           double v0) {
  return traceOf(model, records, v0);
}

EngineTrace traceOfRecords(const PhysicalModel& model, const std::vector<EventRecord>& records,
                           double v0) {
  return traceOf(model, records, v0);
}

EngineTrace traceFrom(const Rig& rig, const ScaledModel& model, const Vec& z0, double t_end,
                      double accuracy) {
  Rig r = rig;
  model.setStart(r, z0);
  r.sim.t_end_s = model.seconds(t_end);
  r.sim.accuracy = accuracy;
  r.sim.integrator = "verner76";
  r.sim.sample_s = r.sim.t_end_s;  // no trajectory wanted: as few rows as the schedule allows
  RecordSink sink;
  const RunReport rep = runDirectModel(r, sink);
  EngineTrace trace = traceOf(model, sink.records, z0(ScaledModel::kV));
  trace.complete = rep.complete;
  trace.failure = rep.failure;
  trace.steps = rep.counts.steps;
  return trace;
}

}  // namespace metrosync::orbit
