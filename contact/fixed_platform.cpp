// A platform bolted to the table, {law: fixed}: it never moves (Coulomb with mu -> infinity).
#include <cmath>

#include "contact/law_kind.h"
#include "contact/law_registry.h"

namespace metrosync {

namespace {

class FixedPlatform final : public LawKind {
 public:
  const char* name() const override { return "fixed"; }
  const std::vector<LawParameter>& parameters() const override {
    static const std::vector<LawParameter> ps;
    return ps;
  }
  PlatformFriction platform(const std::vector<double>& v, double N) const override {
    return PlatformFriction(*this, constants(v, N), {false, false, false, false});
  }
  double force(const LawConstants&, double, PlatformMode) const override { return 0.0; }
  double forceSlope(const LawConstants&, double, PlatformMode) const override { return 0.0; }
  LawGradient forceGradient(const LawConstants&, double, PlatformMode) const override { return {}; }
  SlowResponse slowResponse(const std::vector<double>&) const override {
    return SlowResponse::constant({0.0, 0.0});
  }
  bool holdsDrive(const std::vector<double>&, double) const override { return true; }
  std::optional<double> reportedMu() const override { return HUGE_VAL; }
};

}  // namespace

const LawKind& fixedPlatformLaw() {
  static const FixedPlatform law;
  return law;
}

}  // namespace metrosync
