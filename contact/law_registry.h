// Every friction law a rig file may name (platform.friction.law), one line each. A law's file in
// contact/ defines the function named here, returning its LawKind (contact/law_kind.h).
#pragma once

#include <string>
#include <vector>

#include "contact/law_kind.h"

// clang-format off
#define METROSYNC_FRICTION_LAWS(X) \
  X(coulombLaw)       /* contact/coulomb.cpp:        {law: coulomb, mu}            */ \
  X(staticCoulombLaw) /* contact/static_coulomb.cpp: {law: coulomb, mu, mu_static} */ \
  X(viscousLaw)       /* contact/viscous.cpp:        {law: viscous, c}             */ \
  X(noFrictionLaw)    /* contact/no_friction.cpp:    {law: none}                   */ \
  X(fixedPlatformLaw) /* contact/fixed_platform.cpp: {law: fixed}                  */ \
  X(stribeckLaw)      /* contact/stribeck.cpp:       {law: stribeck, mu, mu_static, ...}  */ \
  /* a new law: one line above this one, ending in a backslash */
// clang-format on

namespace metrosync {

#define METROSYNC_DECLARE_LAW(f) const LawKind& f();
METROSYNC_FRICTION_LAWS(METROSYNC_DECLARE_LAW)
#undef METROSYNC_DECLARE_LAW

// The registered laws, in the order above.
const std::vector<const LawKind*>& lawRegistry();
// The distinct law names, in registry order (for messages).
std::vector<std::string> lawNames();
// The names of the laws with parameter `key`, joined by " or " (for "only with law: ...").
std::string lawsWithKey(const std::string& key);
// Every parameter key of every law, once each (the rig schema's platform.friction keys).
std::vector<std::string> lawKeys();
// The law named `name` that takes every key in `keys` and has every parameter it requires
// among them (any order; a parameter with a default may be left out); nullptr if none.
const LawKind* findLaw(const std::string& name, const std::vector<std::string>& keys);

}  // namespace metrosync
