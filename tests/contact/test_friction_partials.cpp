// Each registered friction law's partials (contact/friction_partials.h) against central
// differences of the law's own engine form (FrictionLaw::platform): the force in every mode at a
// slip velocity, and the static bound, in the law's parameters, the normal force and the velocity.
// A law added to the registry without its partials fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/friction_partials.h"
#include "contact/law_registry.h"

namespace metrosync {
namespace {

// The laws are smooth in their parameters away from a mode switch: central differences over
// kStep have O(kStep^2) truncation and O(1e-16 / kStep) rounding of O(1) values.
constexpr double kStep = 1e-6;
constexpr double kAgree = 1e-8;

double force(const FrictionLaw& law, double N, double v, PlatformMode mode) {
  return law.platform(N).force(v, mode);
}
double staticBound(const FrictionLaw& law, double N) {
  const PlatformFriction f = law.platform(N);
  return f.setValued() ? f.dry.staticBound() : 0.0;
}

TEST(FrictionPartials, EveryLawsAreItsEngineFormsDifferences) {
  const double N = 3.03;
  for (const LawKind* kind : lawRegistry()) {
    std::vector<double> values;
    for (std::size_t i = 0; i < kind->parameters().size(); ++i) values.push_back(0.2 + 0.1 * i);
    const FrictionLaw law(*kind, values);
    for (PlatformMode mode :
         {PlatformMode::Stuck, PlatformMode::SlipPositive, PlatformMode::SlipNegative}) {
      const double v = 0.3 * static_cast<int>(mode) + (mode == PlatformMode::Stuck ? 0.0 : 0.1);
      FrictionPartials p;
      ASSERT_TRUE(frictionPartials(law, N, v, mode, p)) << kind->name() << ": no partials";
      ASSERT_EQ(p.force_per_value.size(), values.size());
      ASSERT_EQ(p.static_bound_per_value.size(), values.size());
      const auto near = [&](double exact, double fd, const char* what) {
        EXPECT_NEAR(exact, fd, kAgree * std::max(1.0, std::abs(fd)))
            << kind->name() << " mode " << static_cast<int>(mode) << ": " << what;
      };
      near(p.force_per_velocity,
           (force(law, N, v + kStep, mode) - force(law, N, v - kStep, mode)) / (2 * kStep),
           "dF/dv");
      near(p.force_per_normal_force,
           (force(law, N + kStep, v, mode) - force(law, N - kStep, v, mode)) / (2 * kStep),
           "dF/dN");
      near(p.static_bound_per_normal_force,
           (staticBound(law, N + kStep) - staticBound(law, N - kStep)) / (2 * kStep), "dB/dN");
      for (std::size_t i = 0; i < values.size(); ++i) {
        std::vector<double> hi = values, lo = values;
        hi[i] += kStep;
        lo[i] -= kStep;
        const FrictionLaw a(*kind, hi), b(*kind, lo);
        near(p.force_per_value[i], (force(a, N, v, mode) - force(b, N, v, mode)) / (2 * kStep),
             "dF/dvalue");
        near(p.static_bound_per_value[i], (staticBound(a, N) - staticBound(b, N)) / (2 * kStep),
             "dB/dvalue");
      }
    }
  }
}

}  // namespace
}  // namespace metrosync
