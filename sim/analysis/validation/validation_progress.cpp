#include "sim/analysis/validation/validation_progress.h"

#include "base/number_text.h"

namespace metrosync {

void ValidationLog::run(const std::string& what, const ModelRun& r) {
  std::string s = what + ": " + (r.report.complete ? toString(r.verdict.regime) : "FAILED");
  s += " (" + numberText(r.report.wall_seconds, 1, Notation::Fixed) + " s)";
  if (!r.report.complete) s += " - " + r.report.failure;
  say(s);
}

}  // namespace metrosync
