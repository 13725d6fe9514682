// Every registered friction law's derivatives (contact/platform_friction.h) against central
// differences of its own force and bounds: dF/dv (the periodic orbits' Jacobians), dF/d(each
// parameter) and dF/dN (the fit's variational equations, issue 36), d(static bound)/d(each
// parameter, N). Random laws, normal forces and slip velocities; none while stuck.
//
// Tolerance: a central difference with step h = 1e-6 of the variable's size has truncation error
// ~h^2 |F'''| / 6 and rounding ~1e-16 |F| / h: ~1e-10 relative for these smooth forces of O(1)
// size and scales; 1e-7 relative (to the derivative, or to |F| / scale where the derivative is
// near 0) leaves a wide margin and still catches any wrong factor or sign.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "contact/friction_law.h"
#include "contact/law_registry.h"

namespace metrosync {
namespace {

constexpr double kRel = 1e-7;

// A law of `kind` with values in (0.2, 3), ascending (mu_static >= mu, and each law's rules).
FrictionLaw randomLaw(const LawKind& kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> d(0.2, 3.0);
  std::vector<double> v;
  for (std::size_t k = 0; k < kind.parameters().size(); ++k) v.push_back(d(rng));
  std::sort(v.begin(), v.end());
  return FrictionLaw(kind, v);
}

double central(const std::function<double(double)>& f, double x) {
  const double h = 1e-6 * std::max(1.0, std::abs(x));
  return (f(x + h) - f(x - h)) / (2 * h);
}

void expectClose(double exact, double diff, double scale, const std::string& what) {
  EXPECT_NEAR(exact, diff, kRel * std::max(std::abs(diff), scale)) << what;
}

TEST(LawDerivatives, EveryLawsForceSlopeAndGradientsMatchDifferences) {
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<double> speed(0.05, 4.0), normal(0.5, 20.0);
  for (const LawKind* kind : lawRegistry()) {
    for (int trial = 0; trial < 50; ++trial) {
      const FrictionLaw law = randomLaw(*kind, rng);
      const double N = normal(rng);
      const double v = (trial % 2 ? 1 : -1) * speed(rng);
      const PlatformMode m = v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
      const PlatformFriction f = law.platform(N);
      const std::string what = std::string(law.name()) + " trial " + std::to_string(trial);
      const double scale = std::abs(f.force(v, m)) + 1e-12;
      expectClose(f.forceSlope(v, m), central([&](double u) { return f.force(u, m); }, v),
                  scale / std::abs(v), what + " dF/dv");
      const LawGradient g = f.forceGradient(v, m), gs = f.staticBoundGradient();
      for (std::size_t k = 0; k < law.values().size(); ++k) {
        const std::string key = law.parameters()[k].key;
        auto at = [&](double x) { return law.with(key, x).platform(N); };
        expectClose(g.values[k],
                    central([&](double x) { return at(x).force(v, m); }, law.values()[k]),
                    scale / law.values()[k], what + " dF/d" + key);
        if (f.setValued())
          expectClose(
              gs.values[k],
              central([&](double x) { return at(x).bounds().staticBound(); }, law.values()[k]),
              f.bounds().staticBound() / law.values()[k], what + " dS/d" + key);
      }
      for (std::size_t k = law.values().size(); k < g.values.size(); ++k)
        EXPECT_EQ(g.values[k], 0.0) << what << ": beyond the law's parameters";
      expectClose(g.normal_force, central([&](double n) { return law.platform(n).force(v, m); }, N),
                  scale / N, what + " dF/dN");
      if (f.setValued())
        expectClose(gs.normal_force,
                    central([&](double n) { return law.platform(n).bounds().staticBound(); }, N),
                    f.bounds().staticBound() / N, what + " dS/dN");
      // stuck: the holding force is a constraint, the law contributes nothing
      if (f.setValued()) {
        EXPECT_EQ(f.force(0.0, PlatformMode::Stuck), 0.0) << what;
        const LawGradient stuck = f.forceGradient(0.0, PlatformMode::Stuck);
        for (double d : stuck.values) EXPECT_EQ(d, 0.0) << what;
        EXPECT_EQ(stuck.normal_force, 0.0) << what;
      }
    }
  }
}

// Coulomb's law by name: -mu N sign(v) whatever the speed; its derivatives in closed form.
TEST(LawDerivatives, CoulombsInClosedForm) {
  const PlatformFriction f = FrictionLaw::coulomb(0.3).platform(10.0);
  EXPECT_TRUE(f.constantSlipForce());
  EXPECT_EQ(f.forceSlope(2.0, PlatformMode::SlipPositive), 0.0);
  const LawGradient g = f.forceGradient(2.0, PlatformMode::SlipPositive);
  EXPECT_EQ(g.values[0], -10.0);
  EXPECT_EQ(g.normal_force, -0.3);
  EXPECT_EQ(f.forceGradient(-2.0, PlatformMode::SlipNegative).values[0], 10.0);
  EXPECT_EQ(f.staticBoundGradient().values[0], 10.0);
  const PlatformFriction viscous = FrictionLaw::viscous(0.5).platform(10.0);
  EXPECT_EQ(viscous.forceSlope(2.0, PlatformMode::Stuck), -0.5);
  EXPECT_EQ(viscous.forceGradient(2.0, PlatformMode::Stuck).values[0], -2.0);
  EXPECT_EQ(viscous.staticBoundGradient().values[0], 0.0);  // no bound
}

}  // namespace
}  // namespace metrosync
