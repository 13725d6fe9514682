// No friction at all, {law: none}: the platform rolls freely (Coulomb with mu = 0 in force).
#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

class NoFriction final : public LawKind {
 public:
  const char* name() const override { return "none"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps;
    return ps;
  }
  PlatformFriction platform(const std::vector<double>& v, double N) const override {
    return PlatformFriction(*this, constants(v, N), {true, false, false, false});
  }
  double force(const LawConstants&, double, PlatformMode) const override { return 0.0; }
  double forceSlope(const LawConstants&, double, PlatformMode) const override { return 0.0; }
  LawGradient forceGradient(const LawConstants&, double, PlatformMode) const override { return {}; }
  SlowResponse slowResponse(const std::vector<double>&) const override {
    return SlowResponse::constant({0.5, 0.0});
  }
  bool holdsDrive(const std::vector<double>&, double) const override { return false; }
  std::optional<double> reportedMu() const override { return 0.0; }
};

}  // namespace

const LawKind& noFrictionLaw() {
  static const NoFriction law;
  return law;
}

}  // namespace metrosync
