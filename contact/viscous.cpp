// Viscous platform friction, {law: viscous, c}: F = -c-bar xdot (the earlier models' law). Its
// averaged response is constant: beta1 = 1 / (2 (1 + c^2)), beta2 = c / (2 (1 + c^2)).
#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

class Viscous final : public LawKind {
 public:
  const char* name() const override { return "viscous"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps = {{"c", kDampingCoefficient,
                                                  "c-bar in N s/m: F = -c-bar xdot",
                                                  "the scaled coefficient c = c-bar / (M omega0)"}};
    return ps;
  }
  // a force of the velocity alone, independent of the normal force
  PlatformFriction platform(const std::vector<double>& v, double N) const override {
    return PlatformFriction(*this, constants(v, N), {true, false, true, false});
  }
  double force(const LawConstants& k, double v, PlatformMode) const override {
    return -k.values[0] * v;
  }
  double forceSlope(const LawConstants& k, double, PlatformMode) const override {
    return -k.values[0];
  }
  LawGradient forceGradient(const LawConstants&, double v, PlatformMode) const override {
    LawGradient g;
    g.values[0] = -v;
    return g;
  }
  SlowResponse slowResponse(const std::vector<double>& v) const override {
    return SlowResponse::constant(viscousResponse(v[0]));
  }
  bool holdsDrive(const std::vector<double>&, double) const override { return false; }
};

}  // namespace

const LawKind& viscousLaw() {
  static const Viscous law;
  return law;
}

}  // namespace metrosync
