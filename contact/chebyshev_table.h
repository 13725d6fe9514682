// A piecewise Chebyshev interpolant of a smooth function of one variable on [0, end]: `pieces`
// equal pieces, each interpolated at its degree + 1 Chebyshev points (of the first kind) and
// evaluated by Clenshaw's recurrence. Built once from the function it replaces; how close it is
// to that function is the caller's to measure (tests/contact). Used for the Coulomb platform's
// stick-slip duration and averaged response, evaluated at every slow-flow right-hand side.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/constants.h"

namespace metrosync {

class ChebyshevTable {
 public:
  template <class F>
  ChebyshevTable(F&& f, double end, int pieces, int degree)
      : end_(end), pieces_(pieces), n_(degree + 1), coef_(static_cast<size_t>(pieces) * n_) {
    std::vector<double> v(n_);
    for (int p = 0; p < pieces_; ++p) {
      const double a = end_ * p / pieces_, b = end_ * (p + 1) / pieces_;
      for (int j = 0; j < n_; ++j)
        v[j] = f(0.5 * (a + b) + 0.5 * (b - a) * std::cos(kPi * (j + 0.5) / n_));
      for (int k = 0; k < n_; ++k) {
        double c = 0.0;
        for (int j = 0; j < n_; ++j) c += v[j] * std::cos(kPi * k * (j + 0.5) / n_);
        coef_[static_cast<size_t>(p) * n_ + k] = (k == 0 ? 1.0 : 2.0) * c / n_;
      }
    }
  }

  // the interpolant at x in [0, end] (clamped to the last piece beyond it)
  double operator()(double x) const {
    const double scaled = x * (pieces_ / end_);
    const int p = std::min(pieces_ - 1, static_cast<int>(scaled));
    const double t = 2.0 * (scaled - p) - 1.0;
    const double* c = &coef_[static_cast<size_t>(p) * n_];
    double b1 = 0.0, b2 = 0.0;
    for (int k = n_ - 1; k >= 1; --k) {
      const double b0 = 2.0 * t * b1 - b2 + c[k];
      b2 = b1;
      b1 = b0;
    }
    return t * b1 - b2 + c[0];
  }

  double end() const { return end_; }

 private:
  double end_;
  int pieces_, n_;
  std::vector<double> coef_;  // (pieces x n), the Chebyshev coefficients of each piece
};

}  // namespace metrosync
