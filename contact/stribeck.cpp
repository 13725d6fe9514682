// Stribeck friction, {law: stribeck, mu, mu_static, stribeck_velocity, exponent} (mu_static >=
// mu, stribeck_velocity > 0, exponent > 0, default 2): a stuck platform holds while the force
// needed is below mu_static-bar M g, as {law: coulomb, mu, mu_static}; a slipping one feels a
// force that falls from the static bound to the kinetic one as its speed grows,
//   F(v) = -sign(v) N (mu + (mu_static - mu) exp(-(|v| / V)^E)),   N = M g,
// continuous at the break-free point (F -> mu_static N as v -> 0) and Coulomb's mu N at |v| >> V.
// V is a velocity (m/s in a physical rig, scaled by x_scale omega0); E a pure number.
//
// With mu_static == mu the slip force is mu N bit for bit (mu + 0 * e == mu), Coulomb's law: the
// slow flow takes its averaged response (eq. d2). Above it no averaged response is derived (the
// falling slip force makes the stick-slip cycle differ from appendix "ac"'s): the slow flow
// refuses the law, naming it.
#include <cmath>

#include "contact/law_gradients.h"
#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

enum Parameter { kMu, kMuStatic, kV, kE };

// u = |v| / V and e = exp(-u^E), the shape the slip force falls along.
struct Shape {
  double u, uE, e;
};

Shape shape(const LawConstants& k, double v) {
  const double u = std::abs(v) / k.values[kV];
  const double uE = std::pow(u, k.values[kE]);
  return {u, uE, std::exp(-uE)};
}

class Stribeck final : public LawKind {
 public:
  const char* name() const override { return "stribeck"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps = {
        {"mu", kFrictionCoefficient,
         "mu-bar, kinetic: |F| -> mu-bar * M_total * g when slipping fast (|v| >> V)",
         "the scaled kinetic coefficient mu = mu-bar / epsilon^{3/2}"},
        {"mu_static", kFrictionCoefficient,
         "static mu-bar, >= mu: a stuck platform holds while |F| < mu_static * M_total * g",
         "the scaled static coefficient, >= mu"},
        {"stribeck_velocity", kVelocity,
         "V in m/s, > 0: the slip speed over which the force falls from static to kinetic",
         "the scaled Stribeck velocity V / (x_scale * omega0), > 0"},
        {"exponent", kPureNumber, "E, > 0: the shape exp(-(|v| / V)^E) (default 2, Gaussian)",
         "E, > 0: the shape exp(-(|v| / V)^E) (default 2, Gaussian)", 2.0}};
    return ps;
  }
  std::optional<LawViolation> check(const std::vector<double>& v) const override {
    if (!(v[kMuStatic] >= v[kMu]))
      return LawViolation{"mu_static", "must be >= mu (static friction is at least the kinetic)"};
    if (!(v[kV] > 0)) return LawViolation{"stribeck_velocity", "must be > 0"};
    if (!(v[kE] > 0)) return LawViolation{"exponent", "must be > 0"};
    return std::nullopt;
  }
  // bounds mu_static N (holding) and mu N (the slip force's limit at high speed)
  PlatformFriction platform(const std::vector<double>& v, double N) const override {
    return PlatformFriction(*this, constants(v, N), {true, true, true, false},
                            SetValuedLaw(v[kMuStatic] * N, v[kMu] * N));
  }
  double force(const LawConstants& k, double v, PlatformMode mode) const override {
    if (mode == PlatformMode::Stuck) return 0.0;
    const double d = k.values[kMuStatic] - k.values[kMu];
    return -((k.values[kMu] + d * shape(k, v).e) * k.normal_force) * static_cast<int>(mode);
  }
  // dF/dv = s N d e E u^(E-1) sign(v) / V: positive (the force's size falls with the speed)
  double forceSlope(const LawConstants& k, double v, PlatformMode mode) const override {
    const double d = k.values[kMuStatic] - k.values[kMu];
    if (mode == PlatformMode::Stuck || d == 0.0 || v == 0.0) return 0.0;
    const Shape s = shape(k, v);
    const double E = k.values[kE];
    return static_cast<int>(mode) * k.normal_force * d * s.e * E * std::pow(s.u, E - 1.0) *
           (v > 0 ? 1.0 : -1.0) / k.values[kV];
  }
  LawGradient forceGradient(const LawConstants& k, double v, PlatformMode mode) const override {
    LawGradient g;
    if (mode == PlatformMode::Stuck) return g;
    const double sN = static_cast<int>(mode) * k.normal_force;
    const double d = k.values[kMuStatic] - k.values[kMu];
    const Shape s = shape(k, v);
    g.values[kMu] = -sN * (1.0 - s.e);
    g.values[kMuStatic] = -sN * s.e;
    // de/dV = e E u^E / V, de/dE = -e u^E ln u (0 at u = 0)
    g.values[kV] = -sN * d * s.e * k.values[kE] * s.uE / k.values[kV];
    g.values[kE] = s.u > 0.0 ? sN * d * s.e * s.uE * std::log(s.u) : 0.0;
    g.normal_force = -static_cast<int>(mode) * (k.values[kMu] + d * s.e);
    return g;
  }
  LawGradient staticBoundGradient(const LawConstants& k) const override {
    return boundGradient(k, kMuStatic);
  }
  SlowResponse slowResponse(const std::vector<double>& v) const override {
    if (v[kMuStatic] == v[kMu]) return SlowResponse::dryFriction(v[kMu]);
    return SlowResponse::refusedDry(
        v[kMu],
        "platform.friction: {law: stribeck} with mu_static > mu: the slow flow's averaged "
        "response is derived for Coulomb's law (mu_static = mu) only; run the full model "
        "(--model full)");
  }
  bool holdsDrive(const std::vector<double>& v, double drive) const override {
    return !(drive > v[kMuStatic]);
  }
  std::optional<double> coulombCoefficient(const std::vector<double>& v) const override {
    return v[kMuStatic] == v[kMu] ? std::optional<double>(v[kMu]) : std::nullopt;
  }
};

}  // namespace

const LawKind& stribeckLaw() {
  static const Stribeck law;
  return law;
}

}  // namespace metrosync
