// The Hopf test function on many eigenvalues: a rig of 32 metronomes has 63, so 1953 pairwise
// sums, whose product under- or overflows a double. The function must still change sign exactly
// when a complex pair crosses the imaginary axis (and keep the sign of Re prod (lambda_i +
// lambda_j) where that product is representable).
#include <gtest/gtest.h>

#include <complex>
#include <vector>

#include "sim/analysis/continuation/test_functions.h"

namespace metrosync::continuation {
namespace {

using Cd = std::complex<double>;

// n_pairs stable complex pairs (small real parts, close frequencies: small pairwise sums), one
// real eigenvalue, and the pair re +- 0.5 i.
CVec spectrum(int n_pairs, double re) {
  std::vector<Cd> ev;
  for (int k = 0; k < n_pairs; ++k) {
    const Cd l(-0.01 - 0.001 * k, 0.05 + 0.002 * k);
    ev.push_back(l), ev.push_back(std::conj(l));
  }
  ev.push_back(-0.02);
  ev.push_back({re, 0.5}), ev.push_back({re, -0.5});
  return Eigen::Map<CVec>(ev.data(), static_cast<Eigen::Index>(ev.size()));
}

Cd directProduct(const CVec& ev) {
  Cd prod = 1.0;
  for (int i = 0; i < ev.size(); ++i)
    for (int j = i + 1; j < ev.size(); ++j) prod *= ev(i) + ev(j);
  return prod;
}

TEST(HopfTestFunction, ChangesSignAtACrossingAmongManyEigenvalues) {
  const CVec before = spectrum(30, -1e-3), after = spectrum(30, 1e-3);  // 63 eigenvalues
  ASSERT_EQ(before.size(), 63);
  const double g0 = hopfTest(before), g1 = hopfTest(after);
  EXPECT_NE(g0, 0.0);
  EXPECT_NE(g1, 0.0);
  EXPECT_LT(g0 * g1, 0.0) << g0 << " " << g1;
  EXPECT_TRUE(std::isfinite(g0) && std::isfinite(g1));
  // no crossing: no sign change
  EXPECT_GT(hopfTest(spectrum(30, -2e-3)) * g0, 0.0);
}

TEST(HopfTestFunction, SignOfTheProductWhereItIsRepresentable) {
  for (double re : {-0.3, -1e-3, 1e-3, 0.3}) {
    const CVec ev = spectrum(3, re);
    const Cd prod = directProduct(ev);
    ASSERT_TRUE(std::isnormal(prod.real()));
    EXPECT_EQ(hopfTest(ev) > 0, prod.real() > 0) << re;
  }
}

}  // namespace
}  // namespace metrosync::continuation
