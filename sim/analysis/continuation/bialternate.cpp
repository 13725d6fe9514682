#include "sim/analysis/continuation/bialternate.h"

#include <stdexcept>

namespace metrosync::continuation {

namespace {

// The index of the pair (p, q), p > q, in the order (1,0), (2,0), (2,1), (3,0), ...
int pairIndex(int p, int q) {
  return p * (p - 1) / 2 + q;
}

// The entry of 2A (.) I at rows (p, q) and columns (r, s), p > q, r > s (Kuznetsov, eq. 10.84).
double entry(const Mat& A, int p, int q, int r, int s) {
  if (r == p && s == q) return A(p, p) + A(q, q);
  if (r == q) return -A(p, s);
  if (s == p) return -A(q, r);
  if (s == q) return A(p, r);  // r != p
  if (r == p) return A(q, s);  // s != q
  return 0.0;
}

}  // namespace

Mat bialternateProduct(const Mat& A) {
  if (A.rows() != A.cols()) throw std::invalid_argument("bialternateProduct: A is not square");
  const int k = static_cast<int>(A.rows());
  Mat B = Mat::Zero(k * (k - 1) / 2, k * (k - 1) / 2);
  for (int p = 1; p < k; ++p)
    for (int q = 0; q < p; ++q)
      for (int r = 1; r < k; ++r)
        for (int s = 0; s < r; ++s) B(pairIndex(p, q), pairIndex(r, s)) = entry(A, p, q, r, s);
  return B;
}

}  // namespace metrosync::continuation
