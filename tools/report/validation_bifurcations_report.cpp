#include "tools/report/validation_bifurcations_report.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "base/number_text.h"

namespace metrosync {

namespace {

std::string valueList(const std::vector<double>& v) {
  std::string s;
  for (double x : v) s += (s.empty() ? "" : ", ") + numberText(x, 4);
  return s;
}

std::string side(const SideCheck& c) {
  return std::string(c.persists ? "persists" : "leaves") + " (distance " +
         numberText(c.distance, 2) + " at " + numberText(c.value, 5) + ")";
}

std::string bracketText(const FullBracket& b) {
  std::string s = "ε = " + numberText(b.epsilon) + ": ";
  if (std::isnan(b.lo)) {
    s += "no change on " + numberText(b.values.front(), 4) + " … " +
         numberText(b.values.back(), 4) + " (all " + b.regimes.front() + ")";
  } else {
    size_t k = 1;
    while (k < b.values.size() && b.values[k] != b.hi) ++k;
    s += "between " + numberText(b.lo, 4) + " (" + b.regimes[k - 1] + ") and " +
         numberText(b.hi, 4) + " (" + b.regimes[k] + ")";
  }
  return s;
}

}  // namespace

void mdBifurcations(std::ostream& md, const std::vector<BifurcationFamilyResult>& families) {
  if (families.empty()) return;
  md << "## 6. Bifurcations of the slow flow (continuation)\n\n"
     << "Each family's locked state is settled from the rig's start and followed by `metrosync "
        "continue`'s continuation; every fold and Hopf point on its branch is checked by slow-flow "
        "runs (τ = 1000) started on the locked state at the point (perturbed by 1e-3) at 1% of "
        "the range below and above it: where the branch is stable on a side of the point, the "
        "state must persist (end within "
     << numberText(kPersistDistance)
     << " of the point's state) on exactly one side. The full model, from the rig's start, "
        "brackets the same transition on a grid of the parameter around the point.\n\n";
  for (const BifurcationFamilyResult& f : families) {
    md << "### " << f.spec.name << " (`" << f.spec.key << "`, scenario " << f.spec.scenario
       << ")\n\n"
       << "Start: " << f.start << ".\n\n";
    if (f.points.empty()) {
      md << "No fold or Hopf point on [" << numberText(f.spec.lo) << ", " << numberText(f.spec.hi)
         << "].\n\n";
      continue;
    }
    md << "| point | " << f.spec.key << " | A | ψ | below | above | check | full model |\n"
       << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (size_t i = 0; i < f.points.size(); ++i) {
      const LocatedPoint& p = f.points[i];
      std::string full;
      if (i < f.full.size())
        for (const FullBracket& b : f.full[i]) full += (full.empty() ? "" : "; ") + bracketText(b);
      md << "| " << p.type << " | " << numberText(p.value, 9) << " | " << valueList(p.A) << " | "
         << valueList(p.psi) << " | " << side(p.below) << " | " << side(p.above) << " | "
         << (!p.checked ? "not checked (unstable on both sides)"
             : p.pass   ? "pass"
                        : "**FAIL**")
         << " | " << (full.empty() ? "not run" : full) << " |\n";
    }
    md << "\n" << f.spec.meaning << "\n\n";
  }
}

nlohmann::json validationBifurcationsJson(const std::vector<BifurcationFamilyResult>& families) {
  nlohmann::json out = nlohmann::json::array();
  for (const BifurcationFamilyResult& f : families) {
    nlohmann::json points = nlohmann::json::array();
    for (size_t i = 0; i < f.points.size(); ++i) {
      const LocatedPoint& p = f.points[i];
      nlohmann::json full = nlohmann::json::array();
      if (i < f.full.size())
        for (const FullBracket& b : f.full[i])
          full.push_back({{"epsilon", b.epsilon},
                          {"values", b.values},
                          {"regimes", b.regimes},
                          {"bracket", std::isnan(b.lo) ? nlohmann::json(nullptr)
                                                       : nlohmann::json({b.lo, b.hi})}});
      auto sideJson = [](const SideCheck& c) {
        return nlohmann::json{
            {"value", c.value}, {"distance", c.distance}, {"persists", c.persists}};
      };
      points.push_back({{"type", p.type},
                        {"value", p.value},
                        {"A", p.A},
                        {"psi", p.psi},
                        {"detail", p.detail},
                        {"below", sideJson(p.below)},
                        {"above", sideJson(p.above)},
                        {"checked", p.checked},
                        {"pass", p.pass},
                        {"full_model", full}});
    }
    out.push_back({{"family", f.spec.name},
                   {"param", f.spec.key},
                   {"scenario", f.spec.scenario},
                   {"start", f.start},
                   {"points", points}});
  }
  return out;
}

}  // namespace metrosync
