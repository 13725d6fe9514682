// base/number_text.h, the one way doubles become text: numberText is printf's %.<p>g, %.<p>e and
// %.<p>f to the byte (every output file and message was written by printf before), and
// roundTripText reads back exactly and is never longer than it needs to be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "base/number_text.h"

namespace metrosync {
namespace {

std::string printed(const char* conversion, int precision, double v) {
  const std::string format = std::string("%.") + std::to_string(precision) + conversion;
  char buf[512];
  std::snprintf(buf, sizeof buf, format.c_str(), v);
  return buf;
}

// Values across the exponent range, with the awkward ones: zeros of both signs, subnormals,
// powers of ten at the switch between %g's fixed and scientific forms, halfway roundings.
std::vector<double> samples() {
  std::vector<double> v = {0.0,
                           -0.0,
                           1.0,
                           -1.0,
                           0.1,
                           0.3,
                           1e-5,
                           1e-4,
                           9.5e-5,
                           99999.95,
                           1e5,
                           1e6,
                           1e15,
                           1e16,
                           1e17,
                           0.5,
                           2.5,
                           0.125,
                           1e-320,
                           5e-324,
                           1.7976931348623157e308,
                           3.141592653589793,
                           6.283185307179586,
                           123456789.0,
                           -2.675e-3};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int k = 0; k < 3000; ++k) v.push_back(mantissa(rng) * std::pow(10.0, exponent(rng)));
  return v;
}

TEST(NumberText, IsPrintfForEveryPrecisionAndNotation) {
  for (double v : samples()) {
    for (int p = 0; p <= 17; ++p) {
      ASSERT_EQ(numberText(v, p), printed("g", p, v)) << "%g, p = " << p;
      ASSERT_EQ(numberText(v, p, Notation::Scientific), printed("e", p, v)) << "%e, p = " << p;
      if (std::abs(v) < 1e30) {
        ASSERT_EQ(numberText(v, p, Notation::Fixed), printed("f", p, v)) << "%f, p = " << p;
      }
    }
  }
  EXPECT_EQ(numberText(0.1), "0.1");  // the default: %g
  EXPECT_EQ(numberText(1.7976931348623157e308, 2, Notation::Fixed),
            printed("f", 2, 1.7976931348623157e308));  // the longest fixed text fits
}

// writeGeneral (Dragonbox's shortest digits rounded, with std::to_chars where the digits dropped
// lie near a half) against printf over every bit pattern's kind: random bits (every exponent,
// subnormals), the rows' usual magnitudes, and values built to sit on or a few ulps beside a
// halfway point of the precision's last digit, where rounding the shortest digits could go wrong.
TEST(NumberText, WriteGeneralIsPrintfOnRandomBitsAndNearHalves) {
  std::mt19937_64 rng(11);
  std::vector<double> v;
  for (int k = 0; k < 20000; ++k) {
    double x;
    const std::uint64_t bits = rng();
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x)) v.push_back(x);
  }
  std::normal_distribution<double> row(0.0, 3.0);
  for (int k = 0; k < 20000; ++k) v.push_back(row(rng));
  std::uniform_int_distribution<long long> digits(100000000000LL, 999999999999LL);
  std::uniform_int_distribution<int> exponent(-20, 20);
  for (int k = 0; k < 20000; ++k) {  // d.ddddddddddd5 x 10^e and its neighbours
    const double half = (static_cast<double>(digits(rng)) + 0.5) * std::pow(10.0, exponent(rng));
    for (double x : {half, std::nextafter(half, 0.0), std::nextafter(half, 1e300)}) {
      v.push_back(x);
      v.push_back(-x);
    }
  }
  // the exact double-double path's edges (base/number_text.cpp, scaledDigits): ties that are
  // exact in binary, integers (trailing zeros), the ends of its range of 10^k and values a few
  // ulps beside the powers of ten where the first digit's exponent changes
  for (const double x : {0.125, 0.375, 2.5, 1.5, 1.0, 7.0, 100.0, 123456.0, 1e11, 1e12, 1e13})
    v.push_back(x);
  for (int e = -25; e <= 16; ++e) {
    const double ten = std::pow(10.0, e);
    double x = ten;
    for (int k = 0; k < 3; ++k) x = std::nextafter(x, 0.0);
    for (int k = 0; k < 6; ++k, x = std::nextafter(x, 1e300)) {
      v.push_back(x);
      v.push_back(x * (1.0 - 5e-13));  // 9.9999999999995..: rounds up to the next power
      v.push_back(x * (1.0 - 4e-13));
    }
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 20000; ++k)  // the rows' magnitudes, uniform in log
    v.push_back(std::pow(10.0, -12.0 + 24.0 * unit(rng)) * (k % 2 ? -1.0 : 1.0));
  char buf[kMaxGeneralChars];
  long checked = 0;
  for (double x : v) {
    for (int p : {1, 3, 6, 10, 12, 14, 15, 16, 17}) {
      const std::string got(buf, writeGeneral(x, p, buf));
      ASSERT_EQ(got, printed("g", p, x)) << "p = " << p << ", bits of " << roundTripText(x);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000000);
}

TEST(NumberText, NonFiniteValues) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(numberText(inf, 12), "inf");
  EXPECT_EQ(numberText(-inf, 3, Notation::Fixed), "-inf");
  // a NaN is "nan" whatever its sign bit (printf would write "-nan" for one of them)
  EXPECT_EQ(numberText(std::nan(""), 12), "nan");
  EXPECT_EQ(numberText(-std::nan(""), 12), "nan");
}

TEST(RoundTripText, ReadsBackExactlyAndIsTheShortestPrintfText) {
  for (double v : samples()) {
    const std::string s = roundTripText(v);
    ASSERT_EQ(std::strtod(s.c_str(), nullptr), v) << s;
    // the first of %.15g, %.16g, %.17g that reads back
    std::string expected;
    for (int p = 15; p <= 17; ++p) {
      expected = printed("g", p, v);
      if (std::strtod(expected.c_str(), nullptr) == v) break;
    }
    ASSERT_EQ(s, expected);
  }
  EXPECT_EQ(roundTripText(0.3), "0.3");
  EXPECT_EQ(roundTripText(0.1 + 0.2), "0.30000000000000004");
}

}  // namespace
}  // namespace metrosync
