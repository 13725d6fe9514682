#include "sim/analysis/validation/validation_results.h"

namespace metrosync {

int ValidationResults::failedChecks() const {
  int n = 0;
  for (const auto& b : betas) n += !b.pass;
  for (const auto& s : scenarios)
    for (const auto& c : s.checks) n += !c.pass;
  for (const auto& c : convergence) n += !c.pass;
  for (const auto& f : bifurcations)
    for (const auto& p : f.points) n += !p.pass;
  if (full_orbits) n += full_orbits->failed();
  return n;
}

int ValidationResults::incompleteRuns() const {
  int n = 0;
  for (const auto& s : scenarios) n += !s.slow.report.complete;
  for (const auto& r : regimes) {
    n += !r.slow.report.complete;
    for (const auto& f : r.full) n += !f.report.complete;
  }
  for (const auto& p : sweep) n += !p.slow.report.complete + !p.full.report.complete;
  for (const auto& c : convergence) n += !c.complete;
  if (experiments) {
    n += !experiments->failure.empty();
    for (const auto& o : experiments->outcomes) n += !o.run.report.complete;
  }
  return n;
}

}  // namespace metrosync
