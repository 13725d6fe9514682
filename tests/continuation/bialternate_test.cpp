// The bialternate product's defining property: its eigenvalues are the pairwise sums
// lambda_i + lambda_j (i < j) of the matrix's eigenvalues, checked on random matrices of several
// sizes (complex pairs included) against Eigen's eigenvalues of the matrix itself.
#include "sim/analysis/continuation/bialternate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <random>
#include <vector>

namespace metrosync::continuation {
namespace {

using Cd = std::complex<double>;

std::vector<Cd> sorted(std::vector<Cd> v) {
  std::sort(v.begin(), v.end(), [](Cd a, Cd b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  });
  return v;
}

TEST(Bialternate, EigenvaluesArePairwiseSums) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k : {2, 3, 4, 5}) {
    Mat A(k, k);
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) A(i, j) = g(rng);
    const CVec lam = A.eigenvalues();
    std::vector<Cd> sums;
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) sums.push_back(lam(i) + lam(j));
    const Mat B = bialternateProduct(A);
    ASSERT_EQ(B.rows(), k * (k - 1) / 2);
    const CVec mu = B.eigenvalues();
    const std::vector<Cd> a = sorted(sums), b = sorted({mu.data(), mu.data() + mu.size()});
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(std::abs(a[i] - b[i]), 0.0, 1e-10) << k;
  }
}

TEST(Bialternate, SingularAtAHopfPair) {
  // eigenvalues +-2i and -1: the bialternate product has the eigenvalue 2i + (-2i) = 0
  Mat A(3, 3);
  A << 0, -2, 0, 2, 0, 0, 0.3, 0.1, -1;
  const Eigen::JacobiSVD<Mat> svd(bialternateProduct(A));
  EXPECT_LT(svd.singularValues().minCoeff(), 1e-12);
}

}  // namespace
}  // namespace metrosync::continuation
