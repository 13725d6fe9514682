// A friction law between the platform and the table, as a value: which law (a kind from the
// registry, contact/law_registry.h) and its parameter values, in the units of the rig it belongs
// to (physical in PlatformSpec, scaled in ScaledParams). It carries everything the rest of the
// code asks of a law: its name and keys (rig files, --set), its JSON, its scaling, the engines'
// law at a normal force (contact/platform_friction.h: force, derivatives, bounds), the slow
// flow's averaged response (contact/slow_response.h), and whether it can hold the platform. Two
// laws are equal when they are the same kind with the same values: every parameter counts, so a
// new one is never ignored by a comparison.
//
// To add a law: one file in contact/ defining its LawKind (contact/law_kind.h), one line in
// contact/law_registry.h. Nothing else changes: readers, writers and engines go through here
// (docs/friction.md, "Adding a law").
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "contact/law_kind.h"
#include "contact/platform_mode.h"

namespace metrosync {

// The rig's scales a parameter's unit is made of (contact/law_kind.h LawUnit; models/scaling.h):
// scaled = physical / (coefficient^c mass^m length^l rate^r).
struct LawScales {
  double coefficient = 1.0;  // eps^{3/2}
  double mass = 1.0;         // M (kg)
  double length = 1.0;       // x_scale (m)
  double rate = 1.0;         // omega0 (1/s)
};

class FrictionLaw {
 public:
  // Coulomb's law with mu = 0 (a rig's default before its file is read).
  FrictionLaw();
  // `values` in the order of kind.parameters(); throws std::invalid_argument on a wrong count.
  FrictionLaw(const LawKind& kind, std::vector<double> values);

  static FrictionLaw coulomb(double mu);
  static FrictionLaw viscous(double c);
  static FrictionLaw none();
  static FrictionLaw fixed();

  const LawKind& kind() const { return *kind_; }
  const char* name() const { return kind_->name(); }
  const std::vector<LawParameter>& parameters() const { return kind_->parameters(); }
  const std::vector<double>& values() const { return values_; }
  bool is(const LawKind& k) const { return kind_ == &k; }
  // The value of parameter `key`; nullopt if the law has no such parameter.
  std::optional<double> value(const std::string& key) const;
  double valueOr(const std::string& key, double fallback) const {
    return value(key).value_or(fallback);
  }
  // The same law with parameter `key` set to v; throws std::invalid_argument if it has none.
  FrictionLaw with(const std::string& key, double v) const;

  FrictionLaw scaled(const LawScales& s) const;    // physical -> scaled
  FrictionLaw physical(const LawScales& s) const;  // scaled -> physical

  // The engines' law at normal force N (coefficients times N; viscous c as is).
  PlatformFriction platform(double normal_force) const {
    return kind_->platform(values_, normal_force);
  }
  bool setValued() const { return platform(1.0).setValued(); }
  bool platformMoves() const { return platform(1.0).platformMoves(); }
  bool exertsForce() const { return platform(1.0).exertsForce(); }
  // mu-bar (or scaled mu) when the law is Coulomb's law (LawKind::coulombCoefficient).
  std::optional<double> coulombCoefficient() const { return kind_->coulombCoefficient(values_); }
  // The rules across parameters (mu_static >= mu); nullopt when they hold.
  std::optional<LawViolation> violation() const { return kind_->check(values_); }

  // Scaled values only:
  SlowResponse slowResponse() const { return kind_->slowResponse(values_); }
  bool holdsDrive(double drive) const { return kind_->holdsDrive(values_, drive); }

  // {"law": name, key: value, ...} in the units of the values.
  nlohmann::json toJson() const;

  friend bool operator==(const FrictionLaw& a, const FrictionLaw& b) {
    return a.kind_ == b.kind_ && a.values_ == b.values_;
  }
  friend bool operator!=(const FrictionLaw& a, const FrictionLaw& b) { return !(a == b); }

 private:
  const LawKind* kind_;
  std::vector<double> values_;
};

}  // namespace metrosync
