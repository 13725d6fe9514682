// models/vector_trig.h against the scalar sin and cos: every length (so every vector width and
// every tail), angles from the pendulums' range out to the large arguments where libmvec switches
// to its slow path, and the special values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "models/vector_trig.h"

namespace metrosync {
namespace {

// libmvec documents a 4 ulp bound for its double sin and cos
constexpr double kUlpBound = 4.0;

double ulps(double got, double want) {
  if (got == want) return 0.0;
  const double ulp =
      std::nextafter(std::abs(want), std::numeric_limits<double>::infinity()) - std::abs(want);
  return std::abs(got - want) / std::max(ulp, std::numeric_limits<double>::denorm_min());
}

void expectMatchesScalar(const std::vector<double>& x) {
  const int n = static_cast<int>(x.size());
  std::vector<double> s(n, -7.0), c(n, -7.0);
  sinCos(x.data(), s.data(), c.data(), n);
  for (int i = 0; i < n; ++i) {
    EXPECT_LE(ulps(s[i], std::sin(x[i])), kUlpBound) << "sin, n = " << n << ", x = " << x[i];
    EXPECT_LE(ulps(c[i], std::cos(x[i])), kUlpBound) << "cos, n = " << n << ", x = " << x[i];
  }
}

TEST(VectorTrig, EveryLengthAndTailMatchesTheScalarFunctions) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-3.5, 3.5);
  for (int n = 0; n <= 41; ++n) {
    std::vector<double> x(n);
    for (double& v : x) v = angle(rng);
    expectMatchesScalar(x);
  }
}

TEST(VectorTrig, LargeAndTinyArgumentsMatchTheScalarFunctions) {
  std::vector<double> x = {0.0,
                           -0.0,
                           1e-300,
                           -1e-20,
                           1e-8,
                           1e5,
                           -3e7,
                           1e15,
                           1e300,
                           -1e300,
                           std::numeric_limits<double>::denorm_min(),
                           6.283185307179586,
                           3.141592653589793,
                           1.5707963267948966};
  for (int k = 0; k < 19; ++k) x.push_back(std::ldexp(1.0, 3 * k) + 0.25);  // up to 2^54
  expectMatchesScalar(x);
}

TEST(VectorTrig, NonFiniteArgumentsGiveNaN) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> x = {
      inf, -inf, std::numeric_limits<double>::quiet_NaN(), 0.5, inf, 0.25, -inf, 1.0, 2.0};
  std::vector<double> s(x.size()), c(x.size());
  sinCos(x.data(), s.data(), c.data(), static_cast<int>(x.size()));
  for (size_t i = 0; i < x.size(); ++i) {
    if (std::isfinite(x[i])) {
      EXPECT_LE(ulps(s[i], std::sin(x[i])), kUlpBound);
      continue;
    }
    EXPECT_TRUE(std::isnan(s[i])) << i;
    EXPECT_TRUE(std::isnan(c[i])) << i;
  }
}

TEST(VectorTrig, BelowTheVectorWidthTheScalarBitsAreKept) {
  // outside the small-angle polynomials' domain, n < kVectorTrigMin goes through std::sin and
  // std::cos themselves: the same bits
  const double x[3] = {2.3, -2.1, 1e-3};
  double s[3], c[3];
  for (int n = 1; n < kVectorTrigMin && n <= 3; ++n) {
    sinCos(x, s, c, n);
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(s[i], std::sin(x[i]));
      EXPECT_EQ(c[i], std::cos(x[i]));
    }
  }
}

// The small-angle polynomials (every |x| <= kSmallAngle): within the same 4 ulp of glibc at every
// length, across the whole domain, at its ends and at the special small values; and the glibc
// path takes over the moment one angle leaves the domain.
TEST(VectorTrig, SmallAnglePolynomialsMatchTheScalarFunctions) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> angle(-kSmallAngle, kSmallAngle);
  for (int n = 1; n <= 41; ++n)
    for (int rep = 0; rep < 50; ++rep) {
      std::vector<double> x(n);
      for (double& v : x) v = angle(rng);
      std::vector<double> s(n), c(n);
      ASSERT_TRUE(smallAngleSinCos(x.data(), s.data(), c.data(), n));
      expectMatchesScalar(x);
    }
  const double d = std::numeric_limits<double>::denorm_min();
  expectMatchesScalar({0.0, -0.0, d, -d, 1e-300, 1e-8, -1e-8, kSmallAngle, -kSmallAngle,
                       std::nextafter(kSmallAngle, 0.0), 0.785398163397448, 1.0, -1.2});
  const double one_out[3] = {0.2, std::nextafter(kSmallAngle, 2.0), -0.4};
  double s[3], c[3];
  EXPECT_FALSE(smallAngleSinCos(one_out, s, c, 3));
  const double nan_in[2] = {0.1, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_FALSE(smallAngleSinCos(nan_in, s, c, 2));
}

// The polynomials' own bound, tighter than libmvec's: within 2 ulp of glibc over 2e6 random angles
// of the domain (Horner's rule and Estrin's scheme, models/vector_trig.h, both measured within 2).
TEST(VectorTrig, SmallAnglePolynomialsAreWithinTwoUlp) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> angle(-kSmallAngle, kSmallAngle);
  double worst_s = 0.0, worst_c = 0.0;
  for (int k = 0; k < 1000000; ++k) {
    const double x[2] = {angle(rng), angle(rng)};
    double s[2], c[2];
    ASSERT_TRUE(smallAngleSinCos(x, s, c, 2));
    for (int i = 0; i < 2; ++i) {
      worst_s = std::max(worst_s, ulps(s[i], std::sin(x[i])));
      worst_c = std::max(worst_c, ulps(c[i], std::cos(x[i])));
    }
  }
  EXPECT_LE(worst_s, 2.0);
  EXPECT_LE(worst_c, 2.0);
  EXPECT_GT(worst_s + worst_c, 0.0);  // not the same functions: the check can see a difference
}

// Mirror-image pendulums (exact antiphase) must get mirror-image sines and equal cosines to the
// last bit, whatever their partners in the same call (the resolver cancels their impulses on the
// platform exactly).
TEST(VectorTrig, SmallAnglesAreOddEvenAndIndependentOfTheirNeighbours) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> angle(-kSmallAngle, kSmallAngle);
  for (int rep = 0; rep < 1000; ++rep) {
    const double a = angle(rng), b = angle(rng), z = angle(rng);
    const double x[3] = {a, -a, b}, y[2] = {z, a};
    double s[3], c[3], s2[2], c2[2];
    sinCos(x, s, c, 3);
    sinCos(y, s2, c2, 2);
    EXPECT_EQ(s[1], -s[0]);
    EXPECT_EQ(c[1], c[0]);
    EXPECT_EQ(s2[1], s[0]);  // lane 1 of another call, next to another angle
    EXPECT_EQ(c2[1], c[0]);
  }
}

TEST(VectorTrig, NamesTheVariantInUse) {
  const std::string v = sinCosVariant();
  EXPECT_TRUE(v == "avx512" || v == "avx2" || v == "sse2" || v == "scalar") << v;
}

}  // namespace
}  // namespace metrosync
