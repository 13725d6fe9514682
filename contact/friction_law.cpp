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

double factor(const LawScales& s, LawScale scale) {
  return scale == LawScale::Coefficient ? s.coefficient : s.viscous;
}

}  // namespace

AveragedResponse SlowResponse::at(double A) const {
  switch (kind) {
    case Kind::Constant:
      return constant;
    case Kind::Coulomb:
      if (mu < 0.0) throw std::invalid_argument("averaged response: mu < 0");
      return coulombResponse(std::fabs(A) / mu);
    case Kind::None:
      break;
  }
  throw std::invalid_argument(why);
}

FrictionLaw::FrictionLaw() : FrictionLaw(coulomb(0.0)) {}

FrictionLaw::FrictionLaw(const LawKind& kind, std::vector<double> values)
    : kind_(&kind), values_(std::move(values)) {
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

// The same operations as models/scaling.cpp always did (a division by eps^{3/2} or M omega0, a
// product on the way back), so that the scaled values keep their bits.
FrictionLaw FrictionLaw::scaled(const LawScales& s) const {
  FrictionLaw out = *this;
  const std::vector<LawParameter>& ps = kind_->parameters();
  for (std::size_t k = 0; k < ps.size(); ++k) out.values_[k] = values_[k] / factor(s, ps[k].scale);
  return out;
}

FrictionLaw FrictionLaw::physical(const LawScales& s) const {
  FrictionLaw out = *this;
  const std::vector<LawParameter>& ps = kind_->parameters();
  for (std::size_t k = 0; k < ps.size(); ++k) out.values_[k] = values_[k] * factor(s, ps[k].scale);
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
