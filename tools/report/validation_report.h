// The report of `metrosync validate` (sim/analysis/validation/validation.h): report.md with its
// tables, a few PNG plots through gnuplot (a missing gnuplot drops the plots, with a warning, never
// the report) and summary.json. Every number in them comes from the ValidationResults passed in.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/validation/validation.h"
#include "tools/report/outputs.h"

namespace metrosync {

struct ReportContext {
  std::string command;   // the exact command line that regenerates the report
  std::string rigs_dir;  // where the shipped rigs were read from
  std::string date;      // when the run ended (UTC, ISO 8601)
  std::string engine;    // the full model's engine (sim/engines/engine.h)
};

// Consecutive sweep points with the same label, collapsed: the regime sequence over mu. The label
// is the regime's name, with ", uncoupled" for an alive state over a platform at rest.
struct RegimeStretch {
  std::string label;
  double mu_from = 0.0, mu_to = 0.0;
};
std::vector<RegimeStretch> regimeSequence(const std::vector<FrictionSweepPoint>& sweep, bool full);

// The markdown of report.md; `plots` are the PNG names written (the report links to those only).
std::string validationReportMarkdown(const ValidationResults& r, const ReportContext& ctx,
                                     const std::vector<std::string>& plots);

// One run of either model as summary.json records it: {model, epsilon, tau_end, complete,
// [failure], regime, final {tau, A, psi}, [platform, platform_stuck_fraction], wall_seconds}.
nlohmann::json modelRunJson(const ModelRun& m);

// {plan, failed_checks, incomplete_runs, wall_seconds, betas[], scenarios[], convergence[],
// regimes[], sweep[]}: the report's numbers for machines.
nlohmann::json validationJson(const ValidationResults& r, const ReportContext& ctx);

// Writes the plots, report.md and summary.json into dir (atomically, file by file). Returns the
// names of the files written.
std::vector<std::string> writeValidationReport(const OutputDir& dir, const ValidationResults& r,
                                               const ReportContext& ctx);

}  // namespace metrosync
