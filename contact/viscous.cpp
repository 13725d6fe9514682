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
    static const std::vector<LawParameter> ps = {{"c", LawScale::Viscous,
                                                  "c-bar in N s/m: F = -c-bar xdot",
                                                  "the scaled coefficient c = c-bar / (M omega0)"}};
    return ps;
  }
  PlatformFriction platform(const std::vector<double>& v, double) const override {
    PlatformFriction f;
    f.kind = PlatformFriction::Kind::Viscous;
    f.viscous.c = v[0];
    return f;
  }
  SlowResponse slowResponse(const std::vector<double>& v) const override {
    SlowResponse r;
    r.kind = SlowResponse::Kind::Constant;
    r.constant = viscousResponse(v[0]);
    return r;
  }
  bool holdsDrive(const std::vector<double>&, double) const override { return false; }
};

}  // namespace

const LawKind& viscousLaw() {
  static const Viscous law;
  return law;
}

}  // namespace metrosync
