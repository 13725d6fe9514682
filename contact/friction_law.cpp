#include "contact/friction_law.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "contact/law_registry.h"

namespace metrosync {

namespace {

int indexOf(const LawKind& kind, const std::string& key) {
  const std::vector<LawParameter>& ps = kind.parameters();
  for (std::size_t k = 0; k < ps.size(); ++k)
    if (key == ps[k].key) return static_cast<int>(k);
  return -1;
}

// (coefficient^c mass^m length^l rate^r) by products in that order, from 1.0: a viscous c's
// factor is 1.0 * M * omega0 = M omega0, a coefficient's eps^{3/2}, bit for bit what
// models/scaling.cpp always divided by.
double power(double base, int exponent, double f) {
  for (int k = 0; k < exponent; ++k) f *= base;
  for (int k = 0; k > exponent; --k) f /= base;
  return f;
}

double factor(const LawScales& s, const LawUnit& u) {
  double f = power(s.coefficient, u.coefficient, 1.0);
  f = power(s.mass, u.mass, f);
  f = power(s.length, u.length, f);
  return power(s.rate, u.rate, f);
}

}  // namespace

FrictionLaw::FrictionLaw() : FrictionLaw(coulomb(0.0)) {}

FrictionLaw::FrictionLaw(const LawKind& kind, std::vector<double> values)
    : kind_(&kind), values_(std::move(values)) {
  if (kind.parameters().size() > static_cast<std::size_t>(kMaxLawParameters))
    throw std::logic_error(std::string("friction law ") + kind.name() + ": more than " +
                           std::to_string(kMaxLawParameters) + " parameters");
  if (values_.size() != kind.parameters().size())
    throw std::invalid_argument(std::string("friction law ") + kind.name() + ": " +
                                std::to_string(kind.parameters().size()) + " values expected");
}

FrictionLaw FrictionLaw::coulomb(double mu) {
  return FrictionLaw(coulombLaw(), {mu});
}
FrictionLaw FrictionLaw::viscous(double c) {
  return FrictionLaw(viscousLaw(), {c});
}
FrictionLaw FrictionLaw::none() {
  return FrictionLaw(noFrictionLaw(), {});
}
FrictionLaw FrictionLaw::fixed() {
  return FrictionLaw(fixedPlatformLaw(), {});
}

std::optional<double> FrictionLaw::value(const std::string& key) const {
  const int k = indexOf(*kind_, key);
  return k < 0 ? std::nullopt : std::optional<double>(values_[k]);
}

FrictionLaw FrictionLaw::with(const std::string& key, double v) const {
  const int k = indexOf(*kind_, key);
  if (k < 0) throw std::invalid_argument(std::string("friction law ") + name() + " has no " + key);
  FrictionLaw out = *this;
  out.values_[k] = v;
  return out;
}

// A division by the parameter's factor (a product on the way back), as models/scaling.cpp always
// did, so that the scaled values keep their bits.
FrictionLaw FrictionLaw::scaled(const LawScales& s) const {
  FrictionLaw out = *this;
  const std::vector<LawParameter>& ps = kind_->parameters();
  for (std::size_t k = 0; k < ps.size(); ++k) out.values_[k] = values_[k] / factor(s, ps[k].unit);
  return out;
}

FrictionLaw FrictionLaw::physical(const LawScales& s) const {
  FrictionLaw out = *this;
  const std::vector<LawParameter>& ps = kind_->parameters();
  for (std::size_t k = 0; k < ps.size(); ++k) out.values_[k] = values_[k] * factor(s, ps[k].unit);
  return out;
}

nlohmann::json FrictionLaw::toJson() const {
  nlohmann::json j;
  j["law"] = name();
  const std::vector<LawParameter>& ps = kind_->parameters();
  for (std::size_t k = 0; k < ps.size(); ++k) j[ps[k].key] = values_[k];
  return j;
}

}  // namespace metrosync
