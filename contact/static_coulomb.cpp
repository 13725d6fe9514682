// Coulomb friction with a static coefficient above the kinetic one, {law: coulomb, mu,
// mu_static} (mu_static >= mu): a stuck platform holds while the force needed is below
// mu_static-bar M g; a slipping one feels mu-bar M g. With mu_static == mu it is Coulomb's law,
// bit for bit. The slow flow's averaged response is derived for mu_static == mu only (paper
// appendix "ac"); above it the slow flow refuses the law.
#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

class StaticCoulomb final : public LawKind {
 public:
  const char* name() const override { return "coulomb"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps = {
        {"mu", LawScale::Coefficient, "mu-bar, kinetic: |F| = mu-bar * M_total * g while slipping",
         "the scaled kinetic coefficient mu = mu-bar / epsilon^{3/2}"},
        {"mu_static", LawScale::Coefficient,
         "static mu-bar, >= mu: a stuck platform holds while |F| < mu_static * M_total * g",
         "the scaled static coefficient, >= mu"}};
    return ps;
  }
  std::optional<LawViolation> check(const std::vector<double>& v) const override {
    if (v[1] >= v[0]) return std::nullopt;
    return LawViolation{"mu_static", "must be >= mu (static friction is at least the kinetic)"};
  }
  PlatformFriction platform(const std::vector<double>& v, double normal_force) const override {
    PlatformFriction f;
    f.kind = PlatformFriction::Kind::SetValued;
    f.dry = SetValuedLaw(v[1] * normal_force, v[0] * normal_force);
    return f;
  }
  SlowResponse slowResponse(const std::vector<double>& v) const override {
    if (v[1] == v[0]) return coulombSlowResponse(v[0]);
    SlowResponse r;
    r.why =
        "platform.friction.mu_static > mu: the slow flow's averaged response is derived "
        "for Coulomb's law (mu_static = mu) only; run the full model (--model full)";
    return r;
  }
  bool holdsDrive(const std::vector<double>& v, double drive) const override {
    return !(drive > v[1]);
  }
};

}  // namespace

const LawKind& staticCoulombLaw() {
  static const StaticCoulomb law;
  return law;
}

}  // namespace metrosync
