// `metrosync run`'s points in the verdict against the careful peer (issue 36), from the
// work-precision points of the method "run" (tools/bench/run_method.h) read back into
// VerdictScene::run: the scenes with `run` as "ours" (so that ratioTable() gives `run` / peer at
// equal final-state error, on the wall clock: `run`'s time is summary.json's wall_seconds; the
// text of that verdict is peer_verdict_report.h's runVerdict()), and at each point of `run` its
// wall_seconds against its engine_seconds and against the direct engine's time with recording
// off at the same integrator and accuracy (the bench's final-state runs). No I/O.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/peer_verdict.h"
#include "tools/bench/speed_targets.h"

namespace metrosync::bench {

// The scenes with `run` points, each with its run points as `ours` (so that ratioTable() gives
// `run` / peer); the others left out.
std::vector<VerdictScene> runAsOurs(const std::vector<VerdictScene>& scenes);

// One point of `run` beside its engine.
struct RunOverhead {
  std::string scene, method;                                    // run:INTEGRATOR:SETTING
  double wall_s = 0.0, engine_s = 0.0, wall_over_engine = 0.0;  // `run`'s medians
  // the direct engine's wall median without samples at the same integrator and setting (NaN: not
  // measured in this run)
  double alone_s = 0.0;
  double overAlone() const { return wall_s / alone_s; }
};
std::vector<RunOverhead> runOverheads(const std::vector<VerdictScene>& scenes);

// runpoints.csv and runpoints.md: every RunOverhead (they need no peer).
std::string runPointsCsv(const std::vector<RunOverhead>& rows);
std::string runPointsMarkdown(const std::vector<RunOverhead>& rows);

}  // namespace metrosync::bench
