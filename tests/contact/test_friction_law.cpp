// The friction law as a value (contact/friction_law.h): compared by kind and every parameter,
// scaled parameter by parameter, written as JSON with its rig-file keys; each registered law's
// engine form agrees with its name; static friction above kinetic reduces to Coulomb's law, bit
// for bit, when its two coefficients are equal.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "contact/friction_law.h"
#include "contact/law_registry.h"

namespace metrosync {
namespace {

TEST(FrictionLaw, ComparesAsAValueOverEveryParameter) {
  EXPECT_EQ(FrictionLaw::coulomb(0.4), FrictionLaw::coulomb(0.4));
  EXPECT_NE(FrictionLaw::coulomb(0.4), FrictionLaw::coulomb(0.5));
  EXPECT_NE(FrictionLaw::none(), FrictionLaw::fixed());
  EXPECT_NE(FrictionLaw::coulomb(0.0), FrictionLaw::none());  // the same force, not the same law
  // a parameter beyond mu counts: laws that differ in mu_static only are different
  const FrictionLaw a(staticCoulombLaw(), {0.4, 0.5}), b(staticCoulombLaw(), {0.4, 0.6});
  EXPECT_NE(a, b);
  EXPECT_EQ(a, a.with("mu_static", 0.5));
  EXPECT_EQ(b, a.with("mu_static", 0.6));
  EXPECT_THROW(FrictionLaw::coulomb(0.4).with("mu_static", 0.5), std::invalid_argument);
  EXPECT_THROW(FrictionLaw(coulombLaw(), {0.4, 0.5}), std::invalid_argument);  // wrong count
}

TEST(FrictionLaw, JsonNamesTheLawAndEachKey) {
  const nlohmann::json j = FrictionLaw(staticCoulombLaw(), {0.25, 0.375}).toJson();
  EXPECT_EQ(j, nlohmann::json::parse(R"({"law": "coulomb", "mu": 0.25, "mu_static": 0.375})"));
  EXPECT_EQ(FrictionLaw::fixed().toJson(), nlohmann::json::parse(R"({"law": "fixed"})"));
  // every registered law: one JSON key per parameter, its value the law's
  for (const LawKind* kind : lawRegistry()) {
    std::vector<double> v;
    for (std::size_t k = 0; k < kind->parameters().size(); ++k) v.push_back(0.5 + k);
    const nlohmann::json lj = FrictionLaw(*kind, v).toJson();
    EXPECT_EQ(lj.size(), 1 + v.size()) << kind->name();
    for (std::size_t k = 0; k < v.size(); ++k)
      EXPECT_EQ(lj.at(kind->parameters()[k].key).get<double>(), v[k]);
  }
}

TEST(FrictionLaw, ScalesEachParameterByItsUnitAndBack) {
  const LawScales s{0.073 * std::sqrt(0.073), 0.3088, 2.1e-4, 20.9};
  const FrictionLaw stiction(staticCoulombLaw(), {6.5e-4, 1.3e-3});
  const FrictionLaw scaled = stiction.scaled(s);
  EXPECT_EQ(*scaled.value("mu"), 6.5e-4 / s.coefficient);
  EXPECT_EQ(*scaled.value("mu_static"), 1.3e-3 / s.coefficient);
  // a damping coefficient by M omega0, the product models/scaling.cpp always divided by
  EXPECT_EQ(*FrictionLaw::viscous(0.05).scaled(s).value("c"), 0.05 / (s.mass * s.rate));
  const FrictionLaw back = scaled.physical(s);
  EXPECT_NEAR(*back.value("mu"), 6.5e-4, 1e-18);
  EXPECT_NEAR(*back.value("mu_static"), 1.3e-3, 1e-18);
}

// Static >= kinetic: the rule the rig loader applies; the engines' bounds are each coefficient
// times the normal force; at equality the engines' law is Coulomb's, bit for bit.
TEST(FrictionLaw, StaticFrictionIsCoulombsLawAtEqualCoefficients) {
  EXPECT_FALSE(FrictionLaw(staticCoulombLaw(), {0.4, 0.4}).violation());
  EXPECT_FALSE(FrictionLaw(staticCoulombLaw(), {0.4, 0.7}).violation());
  const std::optional<LawViolation> v = FrictionLaw(staticCoulombLaw(), {0.4, 0.3}).violation();
  ASSERT_TRUE(v);
  EXPECT_EQ(v->key, "mu_static");
  const PlatformFriction f = FrictionLaw(staticCoulombLaw(), {0.4, 0.7}).platform(3.0);
  EXPECT_TRUE(f.setValued());
  EXPECT_EQ(f.bounds().staticBound(), 0.7 * 3.0);
  EXPECT_EQ(f.bounds().kineticBound(), 0.4 * 3.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> mu(0.0, 2.0), normal(0.0, 50.0);
  for (int k = 0; k < 1000; ++k) {
    const double m = mu(rng), n = normal(rng);
    const SetValuedLaw a = FrictionLaw::coulomb(m).platform(n).bounds();
    const SetValuedLaw b = FrictionLaw(staticCoulombLaw(), {m, m}).platform(n).bounds();
    EXPECT_EQ(a.staticBound(), b.staticBound());
    EXPECT_EQ(a.kineticBound(), b.kineticBound());
    EXPECT_EQ(b.staticBound(), b.kineticBound());
  }
}

TEST(FrictionLaw, HoldsADriveUpToItsStaticBound) {
  EXPECT_TRUE(FrictionLaw::coulomb(0.4).holdsDrive(0.4));  // s = 1: stuck (appendix "ac")
  EXPECT_FALSE(FrictionLaw::coulomb(0.4).holdsDrive(0.41));
  const FrictionLaw stiction(staticCoulombLaw(), {0.4, 0.6});
  EXPECT_TRUE(stiction.holdsDrive(0.5));
  EXPECT_FALSE(stiction.holdsDrive(0.61));
  EXPECT_TRUE(FrictionLaw::fixed().holdsDrive(1e9));
  EXPECT_FALSE(FrictionLaw::none().holdsDrive(0.0));
  EXPECT_FALSE(FrictionLaw::viscous(5.0).holdsDrive(0.0));
}

TEST(LawRegistry, NamesKeysAndTheLawTheKeysChoose) {
  EXPECT_EQ(lawNames(),
            (std::vector<std::string>{"coulomb", "viscous", "none", "fixed", "stribeck"}));
  EXPECT_EQ(lawKeys(),
            (std::vector<std::string>{"mu", "mu_static", "c", "stribeck_velocity", "exponent"}));
  EXPECT_EQ(lawsWithKey("mu_static"), "coulomb or stribeck");
  EXPECT_EQ(findLaw("coulomb", {"mu"}), &coulombLaw());
  EXPECT_EQ(findLaw("coulomb", {"mu_static", "mu"}), &staticCoulombLaw());
  EXPECT_EQ(findLaw("coulomb", {"c"}), nullptr);
  EXPECT_EQ(findLaw("none", {}), &noFrictionLaw());
}

}  // namespace
}  // namespace metrosync
