#include "tools/report/validation_full_orbits_report.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tools/report/report_numbers.h"

namespace metrosync {

namespace {

std::string orbitNumber(double v, int digits = 6) {
  return reportNumber(v, digits, "—");
}

std::string orbitList(const std::vector<double>& v, int digits = 3) {
  std::string s;
  for (double x : v) s += (s.empty() ? "" : ", ") + orbitNumber(x, digits);
  return s;
}

const char* slowName(const std::string& type) {
  return type == "hopf" ? "Hopf" : "fold";
}

void seriesTable(std::ostream& md, const FullOrbitsResult& r) {
  md << "| family | full model (slow flow) | slow flow |";
  for (double e : r.epsilons) md << " ε = " << orbitNumber(e) << " |";
  md << " order | (full − slow)/ε | check |\n|";
  for (size_t k = 0; k < r.epsilons.size() + 6; ++k) md << " --- |";
  md << "\n";
  for (const FullPointSeries& s : r.series) {
    md << "| " << s.family << " (`" << s.key << "`) | " << s.full_type << " ("
       << slowName(s.slow_type) << ") | " << orbitNumber(s.slow, 8) << " |";
    for (const FullPointValue& v : s.values) md << " " << orbitNumber(v.value, 8) << " |";
    md << " " << orbitNumber(s.order, 3) << " | " << orbitNumber(s.constant, 3) << " | "
       << (!s.checked ? "not checked (< 2 ε)"
           : s.pass   ? "pass"
                      : "**fail**")
       << " |\n";
  }
  md << "\n";
  for (const FullPointSeries& s : r.series)
    for (const FullPointValue& v : s.values)
      if (!std::isfinite(v.value))
        md << "- " << s.family << ", " << s.full_type << " at ε = " << orbitNumber(v.epsilon)
           << ": not found (" << v.note << ").\n";
  md << "\n";
}

void asymmetricSection(std::ostream& md, const AsymmetricState& a) {
  md << "### The default rig's asymmetric state\n\n";
  if (a.A.empty()) {
    md << "Not found: " << a.start << "\n\n";
    return;
  }
  md << "The experiment's rig (`" << a.scenario << "`: ε = " << orbitNumber(a.epsilon, 4)
     << ", μ = " << orbitNumber(a.mu, 3)
     << ", started near antiphase) settles onto an asymmetric orbit: "
     << "A = " << orbitList(a.A) << ", ψ = " << orbitList(a.psi) << ", largest multiplier "
     << orbitNumber(a.max_multiplier, 4) << " (" << (a.max_multiplier < 1 ? "stable" : "unstable")
     << "); " << a.start << ".\n\n";
  md << "- **In ε** (down to " << orbitNumber(a.eps_lo) << "): ";
  if (a.eps_folds.empty()) md << "no fold; ";
  for (const FoldValue& f : a.eps_folds)
    md << "a fold of cycles at ε = " << orbitNumber(f.value, 6) << " (A = " << orbitList(f.A)
       << ", ψ = " << orbitList(f.psi) << "); ";
  md << "at ε = " << orbitNumber(a.eps_lo) << " the family's orbit has A = " << orbitList(a.A_lo)
     << ", ψ = " << orbitList(a.psi_lo) << " (" << a.eps_ends << ").\n";
  if (std::isfinite(a.mu_from)) {
    md << "- **In μ**: the orbit exists over μ = " << orbitNumber(a.mu_from, 3) << " … "
       << orbitNumber(a.mu_to, 3) << " (" << a.mu_ends << "); special points: ";
    for (size_t k = 0; k < a.mu_specials.size(); ++k) md << (k ? ", " : "") << a.mu_specials[k];
    md << (a.mu_specials.empty() ? "none" : "") << ".\n";
  }
  md << "- **Exact antiphase** (θ₁ = −θ₂, the platform still, the ticks cancelling): largest "
     << "multiplier " << orbitNumber(a.antiphase_multiplier, 6)
     << " at ε = " << orbitNumber(a.epsilon, 4)
     << "; its symmetry-breaking branch point (an antisymmetric multiplier crosses +1) at ε = "
     << orbitNumber(a.antiphase_branch, 6) << ".\n\n";
  md << "The slow flow from the same start ends at A = " << orbitList(a.A_slow)
     << ", ψ = " << orbitList(a.psi_slow) << ".\n\n";
  const bool s_shape = a.eps_folds.size() == 2 && a.eps_folds[0].stability_changes &&
                       a.eps_folds[1].stability_changes;
  if (s_shape)
    md << "So the asymmetric state is not born where a symmetric orbit breaks its symmetry: "
          "followed down in ε it is the stable upper part of an S-shaped family, which dies in "
          "the fold at ε = "
       << orbitNumber(std::min(a.eps_folds[0].value, a.eps_folds[1].value), 4)
       << " against the family's unstable middle part; that part turns back at ε = "
       << orbitNumber(std::max(a.eps_folds[0].value, a.eps_folds[1].value), 4)
       << " onto the stable lower part, the near-antiphase state the slow flow predicts. Between "
          "the two folds both states are stable (hysteresis in ε); at the rig's ε only the "
          "asymmetric one is left on this family. ";
  else
    md << "Its family in ε has " << a.eps_folds.size() << " fold(s) on the range followed. ";
  md << "The symmetric orbit nearby, exact antiphase, is "
     << (a.antiphase_multiplier < 1 ? "stable" : "unstable")
     << " at the rig's ε: every tick of one metronome jolts the platform loose for a moment "
        "unless the other's cancels it, so a phase error couples the pair through those brief "
        "slips, which the slow flow (averaging over a platform that stays stuck) does not see "
        "and calls neutral; that symmetric orbit breaks its symmetry only at the branch point "
        "above.\n\n";
}

}  // namespace

void mdFullOrbitsSummaryRow(std::ostream& md, const FullOrbitsResult& r) {
  int found = 0, values = 0;
  for (const FullPointSeries& s : r.series)
    for (const FullPointValue& v : s.values) values += 1, found += std::isfinite(v.value);
  md << "| 7. bifurcations of the full model (periodic orbits) | " << found << " of " << values
     << " torus and fold points located on " << r.series.size() << " series; orders in ε fitted; "
     << r.failed() << " outside [" << orbitNumber(kOrderLo, 2) << ", " << orbitNumber(kOrderHi, 2)
     << "]: " << (r.failed() == 0 ? "pass" : "**fail**") << " |\n";
}

void mdFullOrbits(std::ostream& md, const FullOrbitsResult& r) {
  md << "## 7. Bifurcations of the full model (periodic orbits)\n\n"
     << "Each family's locked state is a periodic orbit of the full model: the rig's start is run "
        "until it settles, put on a Poincaré section (the largest pendulum's θ = 0, rising) and "
        "corrected by Newton on the return map, whose Jacobian comes from the variational "
        "equations and the saltation matrices of the ticks and the platform's switches; the "
        "orbit is then followed in the key by pseudo-arclength continuation (`metrosync continue "
        "--model full`, docs/continuation.md). A torus point (a complex pair of Floquet "
        "multipliers leaving the unit circle: the amplitudes start to modulate) is the full "
        "model's counterpart of the slow flow's Hopf point, a fold of cycles that of its fold. "
        "Order: least-squares slope of log |full − slow| against log ε (theory: 1); it passes "
        "in ["
     << orbitNumber(kOrderLo, 2) << ", " << orbitNumber(kOrderHi, 2) << "]. This part took "
     << orbitNumber(r.wall_seconds, 3) << " s.\n\n";
  seriesTable(md, r);
  asymmetricSection(md, r.asymmetric);
}

nlohmann::json validationFullOrbitsJson(const FullOrbitsResult& r) {
  nlohmann::json j;
  j["epsilons"] = r.epsilons;
  j["wall_seconds"] = r.wall_seconds;
  for (const FullPointSeries& s : r.series) {
    nlohmann::json values = nlohmann::json::array();
    for (const FullPointValue& v : s.values)
      values.push_back({{"epsilon", v.epsilon}, {"value", jsonNumber(v.value)}, {"note", v.note}});
    j["series"].push_back({{"family", s.family},
                           {"key", s.key},
                           {"full_type", s.full_type},
                           {"slow_type", s.slow_type},
                           {"slow", jsonNumber(s.slow)},
                           {"values", values},
                           {"order", jsonNumber(s.order)},
                           {"constant", jsonNumber(s.constant)},
                           {"pass", s.pass}});
  }
  const AsymmetricState& a = r.asymmetric;
  nlohmann::json folds = nlohmann::json::array();
  for (const FoldValue& f : a.eps_folds) folds.push_back(f.value);
  j["asymmetric"] = {{"scenario", a.scenario},
                     {"epsilon", a.epsilon},
                     {"mu", a.mu},
                     {"A", a.A},
                     {"psi", a.psi},
                     {"max_multiplier", jsonNumber(a.max_multiplier)},
                     {"epsilon_folds", folds},
                     {"A_at_eps_lo", a.A_lo},
                     {"eps_lo", a.eps_lo},
                     {"mu_from", jsonNumber(a.mu_from)},
                     {"mu_to", jsonNumber(a.mu_to)},
                     {"antiphase_multiplier", jsonNumber(a.antiphase_multiplier)},
                     {"antiphase_branch_epsilon", jsonNumber(a.antiphase_branch)}};
  return j;
}

}  // namespace metrosync
