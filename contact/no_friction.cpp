// No friction at all, {law: none}: the platform rolls freely (Coulomb with mu = 0).
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
  PlatformFriction platform(const std::vector<double>&, double) const override {
    return PlatformFriction{};  // Kind::None
  }
  SlowResponse slowResponse(const std::vector<double>&) const override {
    SlowResponse r;
    r.kind = SlowResponse::Kind::Constant;
    r.constant = {0.5, 0.0};
    return r;
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
