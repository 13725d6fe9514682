// Coulomb's law (eq. frictionlaw), {law: coulomb, mu}: |F| <= mu-bar M g while stuck, F =
// -mu-bar M g sign(xdot) while slipping. Its averaged response is the paper's eq. d2 at s = A / mu.
#include "contact/law_gradients.h"
#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

class Coulomb final : public LawKind {
 public:
  const char* name() const override { return "coulomb"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps = {
        {"mu", kFrictionCoefficient, "mu-bar: |F| = mu-bar * M_total * g",
         "the scaled Coulomb coefficient mu = mu-bar / epsilon^{3/2}"}};
    return ps;
  }
  // one bound mu N; the slip force -mu N mode, computed by PlatformFriction itself (constant_slip)
  PlatformFriction platform(const std::vector<double>& v, double N) const override {
    return PlatformFriction(*this, constants(v, N), {true, true, true, true},
                            SetValuedLaw::coulomb(v[0] * N));
  }
  double force(const LawConstants& k, double, PlatformMode mode) const override {
    return constantSlipForce(k, 0, mode);
  }
  double forceSlope(const LawConstants&, double, PlatformMode) const override { return 0.0; }
  LawGradient forceGradient(const LawConstants& k, double, PlatformMode mode) const override {
    return constantSlipGradient(k, 0, mode);
  }
  LawGradient staticBoundGradient(const LawConstants& k) const override {
    return boundGradient(k, 0);
  }
  SlowResponse slowResponse(const std::vector<double>& v) const override {
    return SlowResponse::dryFriction(v[0]);
  }
  // the slow flow's platform is stuck while s = drive / mu <= 1 (appendix "ac")
  bool holdsDrive(const std::vector<double>& v, double drive) const override {
    return !(drive > v[0]);
  }
  std::optional<double> coulombCoefficient(const std::vector<double>& v) const override {
    return v[0];
  }
};

}  // namespace

const LawKind& coulombLaw() {
  static const Coulomb law;
  return law;
}

}  // namespace metrosync
