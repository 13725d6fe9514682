#include "tools/report/scale_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/constants.h"

namespace metrosync {

namespace {

std::string num(double v, int digits = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace

nlohmann::json scaleJson(const Rig& rig, const ScaledParams& p) {
  nlohmann::json j;
  j["epsilon"] = p.epsilon;
  j["law"] = toString(p.law);
  switch (p.law) {
    case FrictionLaw::Coulomb:
      j["mu"] = p.mu;
      break;
    case FrictionLaw::Viscous:
      j["c"] = p.c;
      break;
    case FrictionLaw::None:
      j["mu"] = 0.0;
      break;  // no friction at all
    case FrictionLaw::Fixed:
      j["mu"] = nullptr;
      break;  // held still: mu -> infinity
  }
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
  os << "  epsilon     " << num(p.epsilon) << "  (m1^2 L1^2 / (I1 M)";
  if (physical) os << ", M = " << num(rig.totalMass()) << " kg";
  os << ")\n";
  os << "  friction    " << toString(p.law);
  if (p.law == FrictionLaw::Coulomb) {
    os << "  mu = " << num(p.mu);
    if (physical) os << "  (mu-bar = " << num(rig.platform.mu_bar) << ")";
  }
  if (p.law == FrictionLaw::Viscous) {
    os << "  c = " << num(p.c);
    if (physical) os << "  (c-bar = " << num(rig.platform.c_Ns_m) << " N s/m)";
  }
  if (rig.platform.spring_N_m > 0) os << "  spring k = " << num(rig.platform.spring_N_m) << " N/m";
  os << "\n";
  if (physical) {
    os << "  time scale  " << num(p.time_scale_s) << " s per unit of t  (fast period "
       << num(2 * kPi * p.time_scale_s) << " s)\n";
    os << "  run         " << num(rig.sim.t_end_s) << " s = " << num(p.tau_end / p.epsilon)
       << " units of t, tau = " << num(p.tau_end) << "\n";
  } else {
    os << "  time scale  1 (a scaled rig runs in scaled time t; fast period 2 pi)\n";
    os << "  run         tau = " << num(p.tau_end) << ", t = " << num(p.tau_end / p.epsilon)
       << "\n";
  }
  os << "\n";

  char line[256];
  std::snprintf(line, sizeof line, "  %-10s %9s %9s %9s %9s %9s %9s %9s %9s\n", "metronome", "nu",
                "J", "J_c", "theta_c", "alpha", "zeta", "A_star", "A(0)");
  os << line;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string name = rig.metronomes[i].name + (p.locked[i] ? " (locked)" : "");
    const std::string a_star = p.A_star[i] ? num(*p.A_star[i]) : "-";
    const double a0 = std::hypot(p.theta0[i], p.thetadot0[i]);
    std::snprintf(line, sizeof line, "  %-10s %9s %9s %9s %9s %9s %9s %9s %9s\n", name.c_str(),
                  num(p.nu[i]).c_str(), num(p.J[i]).c_str(),
                  num(criticalImpulse(p.nu[i], p.theta_c[i])).c_str(), num(p.theta_c[i]).c_str(),
                  num(p.alpha[i]).c_str(), num(p.zeta[i]).c_str(), a_star.c_str(), num(a0).c_str());
    os << line;
  }
  os << "\n  A_star: steady amplitude alone on a still platform (eq. A_star); '-' where J < J_c"
        " = pi nu theta_c\n";
  return os.str();
}

}  // namespace metrosync
