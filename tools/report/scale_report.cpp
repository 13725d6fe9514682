#include "tools/report/scale_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/constants.h"
#include "base/number_text.h"

namespace metrosync {

nlohmann::json scaleJson(const Rig& rig, const ScaledParams& p) {
  nlohmann::json j;
  j["epsilon"] = p.epsilon;
  j.update(p.friction.toJson());  // law and its scaled parameters
  // a law without parameters as the mu it stands for: none 0, fixed infinite (null)
  if (const std::optional<double> mu = p.friction.kind().reportedMu())
    j["mu"] = std::isfinite(*mu) ? nlohmann::json(*mu) : nlohmann::json(nullptr);
  j["nu"] = p.nu;
  j["J"] = p.J;
  j["theta_c"] = p.theta_c;
  j["alpha"] = p.alpha;
  j["zeta"] = p.zeta;
  nlohmann::json a = nlohmann::json::array();
  for (const auto& v : p.A_star) a.push_back(v ? nlohmann::json(*v) : nlohmann::json(nullptr));
  j["A_star"] = a;
  j["time_scale"] = p.time_scale_s;
  return j;
}

std::string scaleText(const Rig& rig, const ScaledParams& p) {
  std::ostringstream os;
  const std::size_t n = p.nu.size();
  os << "rig " << rig.name << " (" << toString(rig.units) << " units, " << n
     << (n == 1 ? " metronome" : " metronomes") << ")\n";
  // physical values in parentheses only for a physical rig (a scaled one has no real M, mu-bar)
  const bool physical = rig.units == Units::Physical;
  os << "  epsilon     " << numberText(p.epsilon, 4) << "  (m1^2 L1^2 / (I1 M)";
  if (physical) os << ", M = " << numberText(rig.totalMass(), 4) << " kg";
  os << ")\n";
  os << "  friction    " << p.friction.name();
  const std::vector<LawParameter>& keys = p.friction.parameters();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string key = keys[k].key, unit = keys[k].unit.text;
    os << "  " << key << " = " << numberText(p.friction.values()[k], 4);
    if (!physical) continue;
    os << "  (" << key << "-bar = " << numberText(rig.platform.friction.values()[k], 4)
       << (unit.empty() ? "" : " " + unit) << ")";
  }
  if (rig.platform.spring_N_m > 0)
    os << "  spring k = " << numberText(rig.platform.spring_N_m, 4) << " N/m";
  os << "\n";
  if (physical) {
    os << "  time scale  " << numberText(p.time_scale_s, 4) << " s per unit of t  (fast period "
       << numberText(2 * kPi * p.time_scale_s, 4) << " s)\n";
    os << "  run         " << numberText(rig.sim.t_end_s, 4)
       << " s = " << numberText(p.tau_end / p.epsilon, 4)
       << " units of t, tau = " << numberText(p.tau_end, 4) << "\n";
  } else {
    os << "  time scale  1 (a scaled rig runs in scaled time t; fast period 2 pi)\n";
    os << "  run         tau = " << numberText(p.tau_end, 4)
       << ", t = " << numberText(p.tau_end / p.epsilon, 4) << "\n";
  }
  os << "\n";

  char line[256];
  std::snprintf(line, sizeof line, "  %-10s %9s %9s %9s %9s %9s %9s %9s %9s\n", "metronome", "nu",
                "J", "J_c", "theta_c", "alpha", "zeta", "A_star", "A(0)");
  os << line;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string name = rig.metronomes[i].name + (p.locked[i] ? " (locked)" : "");
    const std::string a_star = p.A_star[i] ? numberText(*p.A_star[i], 4) : "-";
    const double a0 = std::hypot(p.theta0[i], p.thetadot0[i]);
    std::snprintf(line, sizeof line, "  %-10s %9s %9s %9s %9s %9s %9s %9s %9s\n", name.c_str(),
                  numberText(p.nu[i], 4).c_str(), numberText(p.J[i], 4).c_str(),
                  numberText(criticalImpulse(p.nu[i], p.theta_c[i]), 4).c_str(),
                  numberText(p.theta_c[i], 4).c_str(), numberText(p.alpha[i], 4).c_str(),
                  numberText(p.zeta[i], 4).c_str(), a_star.c_str(), numberText(a0, 4).c_str());
    os << line;
  }
  os << "\n  A_star: steady amplitude alone on a still platform (eq. A_star); '-' where J < J_c"
        " = pi nu theta_c\n";
  return os.str();
}

}  // namespace metrosync
