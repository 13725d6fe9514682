// The peer verdict (tools/bench/peer_verdict.h) as text: ratios.md (the ratio tables at equal
// final-state error, and envelope error where the peer reports one, CPU and wall, the verdict
// overall and per scene, the N-slope, the guards), ratios.csv (every cell) and nslope.csv (every
// point of the N-slope); and `metrosync run` against the peer beside the engine (runVerdict).
#pragma once

#include <string>
#include <vector>

#include "tools/bench/peer_verdict.h"
#include "tools/bench/run_verdict.h"

namespace metrosync::bench {

struct VerdictOptions {
  std::vector<double> errors = {1e-5, 1e-6, 1e-7, 1e-8, 1e-9};  // issue 23's range
  // the scenes that differ only in N (yaml/rigs/bench/)
  std::vector<std::string> slope_scenes = {"experiment-short", "n8", "n32", "n128"};
  std::vector<double> slope_errors = {1e-5, 1e-6, 1e-8};
  Sides sides;
  std::string command;  // how the data was made, for the page ("" = not said)
};

// Everything the verdict computes, once.
struct VerdictPages {
  std::string markdown;  // ratios.md
  // verdicts.md: the headline verdict overall and per scene, its table, the N-slope against its
  // target, the peer's validation (what docs/bench/speed/README.md quotes)
  std::string verdicts_markdown;
  std::string ratios_csv, slope_csv;
  std::string verdict_line;              // the headline verdict (final-state error, CPU)
  std::vector<std::string> scene_lines;  // the headline verdict of each scene, one line each
  std::vector<std::string> slope_lines;  // metrosync's N-slope at each error against its target
  std::vector<std::string> warnings;     // the guards that failed, one line each
  // `metrosync run` against the peer (tools/bench/run_verdict.h): its headline ("" when no scene
  // has run points)
  std::string run_verdict_line;
};

// `metrosync run` against the careful peer (its points: tools/bench/run_verdict.h): what the run
// part of the verdict writes.
struct RunVerdictText {
  std::string line;      // the headline: `run` / peer at equal final-state error, wall time
  std::string markdown;  // the verdict, the side-by-side table, the overhead table
  std::string csv_rows;  // ratios.csv rows of the run side (side = run)
};
// Empty (every field "") when no scene has `run` points.
RunVerdictText runVerdict(const std::vector<VerdictScene>& scenes,
                          const std::vector<double>& errors);

VerdictPages verdictPages(const std::vector<VerdictScene>& scenes, const VerdictOptions& o);

// One line: "MET ..." or "NOT MET ...: where".
std::string verdictLine(const RatioTable& t, const Verdict& v);
// One scene's line: "peer-n2 (N = 2): MET, 2.1-3.4x from 1e-05 to 1e-09" or "... NOT MET: ..."
// or "... the peer was not run: why".
std::string sceneVerdictLine(const RatioRow& row);

// The Markdown table of one measure and clock, cells below the target in bold, then the reason
// of every empty cell.
std::string ratioTableMarkdown(const RatioTable& t);

// ratios.csv's rows of one table; `side`: "engine" (the direct engine) or "run" (`metrosync run`).
std::string ratiosCsvRows(const RatioTable& t, const std::string& side);

}  // namespace metrosync::bench
