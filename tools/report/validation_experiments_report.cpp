#include "tools/report/validation_experiments_report.h"

#include <cmath>
#include <string>
#include <vector>

#include "tools/report/report_numbers.h"

namespace metrosync {

namespace {

// The experiments variant v reproduces, by scenario name.
std::vector<std::string> reproducedBy(const ExperimentsResult& r, const std::string& variant) {
  std::vector<std::string> names;
  for (const ExperimentOutcome& o : r.outcomes)
    if (o.variant == variant && o.reproduces()) names.push_back(o.scenario);
  return names;
}

bool reproduces(const ExperimentsResult& r, const std::string& variant,
                const std::string& scenario) {
  for (const ExperimentOutcome& o : r.outcomes)
    if (o.variant == variant && o.scenario == scenario) return o.reproduces();
  return false;
}

std::string clockName(ExperimentClock c) {
  return c == ExperimentClock::LeavesAntiphase ? "leaves antiphase"
         : c == ExperimentClock::Dies          ? "dies"
                                               : "";
}

std::string outcomeCell(const ExperimentSpec& e, const ExperimentOutcome& o) {
  if (!o.run.report.complete) return "✗ failed: " + o.run.report.failure;
  std::string s =
      std::string(o.reproduces() ? "✓ " : "✗ ") + "**" + toString(o.run.verdict.regime) + "**";
  if (e.clock != ExperimentClock::None)
    s += "<br>" + clockName(e.clock) + ": " +
         (std::isfinite(o.clock_s) ? "at " + numberText(o.clock_s, 3) + " s" : "never");
  const EnvelopeRow& f = o.run.final();
  if (!f.A.empty()) {
    s += "<br>A = " + numberText(f.A[0], 3);
    for (size_t i = 1; i < f.A.size(); ++i) s += ", " + numberText(f.A[i], 3);
  }
  return s;
}

}  // namespace

void mdExperimentsSummaryRow(std::ostream& md, const ExperimentsResult& r) {
  md << "| 8. the paper's experiments (fig. exp1-exp3) | ";
  if (!r.failure.empty()) {
    md << "could not run: " << r.failure << " |\n";
    return;
  }
  for (size_t v = 0; v < r.variants.size(); ++v)
    md << (v ? "; " : "") << r.variants[v].name << ": "
       << reproducedBy(r, r.variants[v].name).size() << " of " << paperExperiments().size()
       << " reproduced";
  md << " |\n";
}

void mdExperiments(std::ostream& md, const ExperimentsResult& r) {
  md << "\n## 8. The paper's experiments\n\n";
  if (!r.failure.empty()) {
    md << "The part could not run: " << r.failure << "\n";
    return;
  }
  md << "Each experiment of section 3C is one of the shipped rigs (docs/experiments.md gives every "
        "number, its source and the conflicts between them), run by the full model over the "
        "rig's own duration in each variant of the rig. An experiment is reproduced when the "
        "final regime is the paper's and, where the paper gives a time, the model's is within a "
        "factor of 2 of it: for exp2 when ψ leaves antiphase (|ψ − π| > "
     << numberText(kLeavesAntiphaseRad)
     << " rad), for exp3 when both amplitudes have fallen below θ_c for good. The variants:\n\n";
  for (const ExperimentVariant& v : r.variants)
    md << "- **" << v.name << "**: " << v.description << "\n";
  md << "\nOne metronome of the experiment's rig alone on a bolted board (the other held in its "
        "box) ticks at "
     << numberText(r.shipped_hz, 5) << " Hz with I = " << numberText(r.shipped_inertia, 4)
     << " kg m² and at " << numberText(r.variant_hz, 5)
     << " Hz with I = " << numberText(r.inertia, 4) << " kg m² (the paper: around "
     << numberText(r.frequency_hz) << " Hz).\n\n| experiment | the paper |";
  for (const ExperimentVariant& v : r.variants) md << " " << v.name << " |";
  md << "\n| --- | --- |";
  for (size_t v = 0; v < r.variants.size(); ++v) md << " --- |";
  md << "\n";
  const auto& exps = paperExperiments();
  for (size_t k = 0; k < exps.size(); ++k) {
    md << "| `" << exps[k].scenario << "`<br>" << exps[k].figure << " | " << exps[k].seen << " |";
    for (size_t v = 0; v < r.variants.size(); ++v)
      md << " " << outcomeCell(exps[k], r.outcomes[k * r.variants.size() + v]) << " |";
    md << "\n";
  }
  md << "\nIn words:";
  for (const ExperimentVariant& v : r.variants) {
    const auto names = reproducedBy(r, v.name);
    md << " " << v.name << " reproduces " << names.size() << " of " << exps.size();
    if (!names.empty()) {
      md << " (";
      for (size_t i = 0; i < names.size(); ++i) md << (i ? ", " : "") << "`" << names[i] << "`";
      md << ")";
    }
    md << ";";
  }
  // exp2 and exp3, the two experiments with a time: which variant reproduces each
  for (size_t k = 0; k < 2; ++k) {
    std::string by;
    for (const ExperimentVariant& v : r.variants)
      if (reproduces(r, v.name, exps[k].scenario)) by += (by.empty() ? "" : ", ") + v.name;
    md << (k ? "; " : " ") << (k ? "exp3" : "exp2") << " ("
       << (k ? "death after about 20 s" : "leaving antiphase after about 10 s") << ") by "
       << (by.empty() ? "no variant" : by);
  }
  md << ".\n";
}

nlohmann::json validationExperimentsJson(const ExperimentsResult& r) {
  nlohmann::json j;
  if (!r.failure.empty()) j["failure"] = r.failure;
  j["frequency_hz"] = jsonNumber(r.frequency_hz);
  j["shipped_hz"] = jsonNumber(r.shipped_hz);
  j["shipped_inertia_kgm2"] = jsonNumber(r.shipped_inertia);
  j["inertia_kgm2"] = jsonNumber(r.inertia);
  j["variant_hz"] = jsonNumber(r.variant_hz);
  for (const ExperimentVariant& v : r.variants)
    j["variants"].push_back({{"name", v.name}, {"description", v.description}, {"sets", v.sets}});
  for (const ExperimentOutcome& o : r.outcomes)
    j["outcomes"].push_back({{"scenario", o.scenario},
                             {"variant", o.variant},
                             {"complete", o.run.report.complete},
                             {"regime", toString(o.run.verdict.regime)},
                             {"clock_s", jsonNumber(o.clock_s)},
                             {"regime_ok", o.regime_ok},
                             {"clock_ok", o.clock_ok},
                             {"reproduces", o.reproduces()}});
  return j;
}

}  // namespace metrosync
