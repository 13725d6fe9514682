// The paper's section-4 figures (f4.1-f4.4) as runs, behind `metrosync figures`: which shipped
// scenarios each figure overlays, with the varied value that names each curve, and each run of
// the slow flow and/or the full model. The runs are validation's own (runSlowModel,
// runFullModelAt of sim/analysis/validation/validation.h, the scenario's shipped epsilon and tau),
// so a figure's numbers are the validation report's. The drawing is tools/report/figures.h; the
// computed regime diagram (figure exp1) is a `metrosync sweep` run by the command.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sim/analysis/validation/validation.h"

namespace metrosync {

// One curve of a figure: a shipped scenario (validation.h's shippedScenarios) and its legend.
struct FigureCurve {
  std::string scenario;  // "f4.3-mu0.3"
  std::string label;     // "μ = 0.3": the varied value
  std::string colour;    // the paper's: black, red, blue (#rrggbb)
};

struct FigureSpec {
  std::string id;       // "f4.3"
  std::string title;    // the figure's title line
  std::string caption;  // the paper's caption, its slips corrected (said in `erratum`)
  std::string erratum;  // what the paper's caption gets wrong, empty when nothing
  std::vector<FigureCurve> curves;
};

// f4.1, f4.2, f4.3, f4.4, in the paper's order.
const std::vector<FigureSpec>& paperFigureSpecs();
// The spec of `id`, or nullptr.
const FigureSpec* findFigureSpec(const std::string& id);

// The computed regime diagram (figure exp1): the rig and the grid that `figures` sweeps.
struct RegimeMapSpec {
  std::string id = "exp1";
  std::string rig_file = "experiment-map.yaml";  // under the shipped rigs' directory
  std::string mu_key = "platform.friction.mu";   // across
  std::string psi0_key = "metronomes.0.start.phi";
  double mu_max = 3.0;
  int mu_count = 40, psi0_count = 40;  // --quick: 12 x 12
  std::string title, caption;
  std::vector<std::string> vary() const;  // the sweep's --vary texts (mu first: across)
};
RegimeMapSpec regimeMapSpec(bool quick);

struct FigureModels {
  bool slow = true, full = false;
};

struct FigureRun {
  FigureCurve curve;
  ScaledParams scaled;
  bool has_slow = false, has_full = false;
  ModelRun slow, full;  // at the scenario's shipped epsilon and tau
};

struct FigureResult {
  FigureSpec spec;
  std::vector<FigureRun> runs;
};

// Runs every curve of `figures` for the models asked, on `jobs` threads (the results do not
// depend on jobs). `scenarios` must hold every scenario the figures name (std::invalid_argument
// otherwise). `progress` gets one line per run.
std::vector<FigureResult> runPaperFigures(const std::vector<FigureSpec>& figures,
                                          const std::vector<Scenario>& scenarios,
                                          const ValidationEngines& engines, FigureModels models,
                                          int jobs,
                                          const std::function<void(const std::string&)>& progress);

}  // namespace metrosync
