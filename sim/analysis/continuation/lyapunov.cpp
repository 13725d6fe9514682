#include "sim/analysis/continuation/lyapunov.h"

#include <cmath>
#include <limits>

#include "sim/analysis/continuation/derivatives.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
using CMat = Eigen::MatrixXcd;

// Steps of the multilinear differences: B's error is O(h^2) + eps/h^2, C's O(h^2) + eps/h^3;
// 1e-3 keeps both below ~1e-6 relative for O(1) fields.
constexpr double kStepB = 1e-4;
constexpr double kStepC = 1e-3;

struct Forms {
  const std::function<Vec(const Vec&)>& f;
  const Vec& y;
  Vec B(const Vec& u, const Vec& v) const {
    const double h = kStepB;
    return (f(y + h * u + h * v) - f(y + h * u - h * v) - f(y - h * u + h * v) +
            f(y - h * u - h * v)) /
           (4 * h * h);
  }
  Vec C(const Vec& u, const Vec& v, const Vec& w) const {
    const double h = kStepC;
    Vec sum = Vec::Zero(y.size());
    for (int a : {1, -1})
      for (int b : {1, -1})
        for (int c : {1, -1}) sum += double(a * b * c) * f(y + h * (a * u + b * v + c * w));
    return sum / (8 * h * h * h);
  }
  // B of two complex vectors, by bilinearity
  CVec Bc(const CVec& u, const CVec& v) const {
    const Vec ur = u.real(), ui = u.imag(), vr = v.real(), vi = v.imag();
    return (B(ur, vr) - B(ui, vi)).cast<Cd>() + Cd(0, 1) * (B(ur, vi) + B(ui, vr)).cast<Cd>();
  }
};

}  // namespace

double firstLyapunovCoefficient(const std::function<Vec(const Vec&)>& f, const Vec& y0) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Mat A = jacobianOf(f, y0);
  Eigen::EigenSolver<Mat> es(A);
  int k = -1;
  for (int i = 0; i < A.rows(); ++i)
    if (es.eigenvalues()(i).imag() > 0 &&
        (k < 0 || std::abs(es.eigenvalues()(i).real()) < std::abs(es.eigenvalues()(k).real())))
      k = i;
  if (k < 0) return nan;
  const double w = es.eigenvalues()(k).imag();
  const int m = static_cast<int>(A.rows());
  const CMat Ac = A.cast<Cd>();
  CVec q = es.eigenvectors().col(k);
  q.normalize();
  // p: the eigenvector of A^T for -i w (A^T p = conj(i w) p), scaled so that pbar . q = 1
  Eigen::ComplexEigenSolver<CMat> et(Ac.transpose());
  int kp = 0;
  for (int i = 1; i < m; ++i)
    if (std::abs(et.eigenvalues()(i) - Cd(0, -w)) < std::abs(et.eigenvalues()(kp) - Cd(0, -w)))
      kp = i;
  CVec p = et.eigenvectors().col(kp);
  p /= std::conj(p.dot(q));  // Eigen's dot conjugates its first argument: p.dot(q) = pbar . q
  const Forms F{f, y0};
  const Vec qr = q.real(), qi = q.imag();
  const Vec Bqqbar = F.B(qr, qr) + F.B(qi, qi);
  const CVec Bqq = F.Bc(q, q);
  const CVec Cqqqbar = (F.C(qr, qr, qr) + F.C(qr, qi, qi)).cast<Cd>() +
                       Cd(0, 1) * (F.C(qr, qr, qi) + F.C(qi, qi, qi)).cast<Cd>();
  const CVec s1 = A.partialPivLu().solve(Bqqbar).cast<Cd>();
  const CVec s2 = (Cd(0, 2 * w) * CMat::Identity(m, m) - Ac).partialPivLu().solve(Bqq);
  const Cd value = p.dot(Cqqqbar) - 2.0 * p.dot(F.Bc(q, s1)) + p.dot(F.Bc(q.conjugate(), s2));
  return value.real() / (2 * w);
}

}  // namespace metrosync::continuation
