// Coulomb friction with a static coefficient above the kinetic one, {law: coulomb, mu,
// mu_static} (mu_static >= mu): a stuck platform holds while the force needed is below
// mu_static-bar M g; a slipping one feels mu-bar M g. With mu_static == mu it is Coulomb's law,
// bit for bit. The slow flow's averaged response is derived for mu_static == mu only (paper
// appendix "ac"); above it the slow flow refuses the law.
#include "contact/law_gradients.h"
#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

class StaticCoulomb final : public LawKind {
 public:
  const char* name() const override { return "coulomb"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps = {
        {"mu", kFrictionCoefficient, "mu-bar, kinetic: |F| = mu-bar * M_total * g while slipping",
         "the scaled kinetic coefficient mu = mu-bar / epsilon^{3/2}"},
        {"mu_static", kFrictionCoefficient,
         "static mu-bar, >= mu: a stuck platform holds while |F| < mu_static * M_total * g",
         "the scaled static coefficient, >= mu"}};
    return ps;
  }
  std::optional<LawViolation> check(const std::vector<double>& v) const override {
    if (v[1] >= v[0]) return std::nullopt;
    return LawViolation{"mu_static", "must be >= mu (static friction is at least the kinetic)"};
  }
  // bounds mu_static N (holding) and mu N (slipping: the constant slip force)
  PlatformFriction platform(const std::vector<double>& v, double N) const override {
    return PlatformFriction(*this, constants(v, N), {true, true, true, true},
                            SetValuedLaw(v[1] * N, v[0] * N));
  }
  double force(const LawConstants& k, double, PlatformMode mode) const override {
    return constantSlipForce(k, 0, mode);
  }
  double forceSlope(const LawConstants&, double, PlatformMode) const override { return 0.0; }
  LawGradient forceGradient(const LawConstants& k, double, PlatformMode mode) const override {
    return constantSlipGradient(k, 0, mode);
  }
  LawGradient staticBoundGradient(const LawConstants& k) const override {
    return boundGradient(k, 1);
  }
  SlowResponse slowResponse(const std::vector<double>& v) const override {
    if (v[1] == v[0]) return SlowResponse::dryFriction(v[0]);
    return SlowResponse::refusedDry(
        v[0],
        "platform.friction.mu_static > mu: the slow flow's averaged response is derived "
        "for Coulomb's law (mu_static = mu) only; run the full model (--model full)");
  }
  bool holdsDrive(const std::vector<double>& v, double drive) const override {
    return !(drive > v[1]);
  }
  std::optional<double> coulombCoefficient(const std::vector<double>& v) const override {
    return v[1] == v[0] ? std::optional<double>(v[0]) : std::nullopt;
  }
};

}  // namespace

const LawKind& staticCoulombLaw() {
  static const StaticCoulomb law;
  return law;
}

}  // namespace metrosync
