// Coulomb's law (eq. frictionlaw), {law: coulomb, mu}: |F| <= mu-bar M g while stuck, |F| =
// mu-bar M g while slipping. Its averaged response is the paper's eq. d2 at s = A / mu.
#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

class Coulomb final : public LawKind {
 public:
  const char* name() const override { return "coulomb"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps = {
        {"mu", LawScale::Coefficient, "mu-bar: |F| = mu-bar * M_total * g",
         "the scaled Coulomb coefficient mu = mu-bar / epsilon^{3/2}"}};
    return ps;
  }
  PlatformFriction platform(const std::vector<double>& v, double normal_force) const override {
    PlatformFriction f;
    f.kind = PlatformFriction::Kind::SetValued;
    f.dry = SetValuedLaw::coulomb(v[0] * normal_force);
    return f;
  }
  SlowResponse slowResponse(const std::vector<double>& v) const override {
    return coulombSlowResponse(v[0]);
  }
  // the slow flow's platform is stuck while s = drive / mu <= 1 (appendix "ac")
  bool holdsDrive(const std::vector<double>& v, double drive) const override {
    return !(drive > v[0]);
  }
};

}  // namespace

SlowResponse coulombSlowResponse(double mu) {
  SlowResponse r;
  if (mu == 0.0) {  // no friction at all: the free platform's response
    r.kind = SlowResponse::Kind::Constant;
    r.constant = {0.5, 0.0};
  } else {
    r.kind = SlowResponse::Kind::Coulomb;
    r.mu = mu;
  }
  return r;
}

const LawKind& coulombLaw() {
  static const Coulomb law;
  return law;
}

}  // namespace metrosync
