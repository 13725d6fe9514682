#include "sim/analysis/continuation/shooting.h"

#include <algorithm>
#include <limits>

#include "sim/analysis/continuation/derivatives.h"
#include "sim/ode/rk_stepper.h"

namespace metrosync::continuation {

namespace {

struct FieldRhs : ode::OdeRhs {
  const CycleField& f;
  double p;
  Vec y, dy;
  FieldRhs(const CycleField& field, double param) : f(field), p(param), y(field.n), dy(field.n) {}
  void eval(const double* in, double* out) override {
    for (int i = 0; i < f.n; ++i) y(i) = in[i];
    dy = f.rhs(y, p);
    for (int i = 0; i < f.n; ++i) out[i] = dy(i);
  }
};

}  // namespace

Vec flowMap(const CycleField& f, const Vec& y0, double T, double p, int steps,
            std::vector<Vec>* orbit) {
  FieldRhs rhs(f, p);
  ode::RkStepper stepper(ode::rkTableau("verner76"), f.n, rhs);
  stepper.setTolerances(1.0, std::vector<double>(f.n, 1.0));  // fixed steps: no control
  stepper.restart(0.0, y0.data());
  const double h = T / steps;
  for (int k = 0; k < steps; ++k) {
    stepper.attempt(h);
    stepper.advance();
    if (orbit) orbit->push_back(Eigen::Map<const Vec>(stepper.y(), f.n));
  }
  return Eigen::Map<const Vec>(stepper.y(), f.n);
}

Vec MultipleShooting::residual(const Vec& u, double p) const {
  const int n = f_.n, M = kSegments;
  const double tau = u(M * n) / M;
  Vec r(M * n);
  for (int j = 0; j < M; ++j)
    r.segment(j * n, n) =
        flowMap(f_, u.segment(j * n, n), tau, p, kStepsPerArc) - u.segment(((j + 1) % M) * n, n);
  return r;
}

Mat MultipleShooting::jacobian(const Vec& u, double p, Mat* monodromy) const {
  const int n = f_.n, M = kSegments;
  const double tau = u(M * n) / M;
  Mat J = Mat::Zero(M * n, M * n + 1);
  if (monodromy) *monodromy = Mat::Identity(n, n);
  for (int j = 0; j < M; ++j) {
    const Vec yj = u.segment(j * n, n);
    const Mat A =
        jacobianOf([&](const Vec& y) { return flowMap(f_, y, tau, p, kStepsPerArc); }, yj);
    J.block(j * n, j * n, n, n) += A;
    J.block(j * n, ((j + 1) % M) * n, n, n) -= Mat::Identity(n, n);
    // d phi / d T = f(phi) / M
    J.block(j * n, M * n, n, 1) = f_.rhs(flowMap(f_, yj, tau, p, kStepsPerArc), p) / M;
    if (monodromy) *monodromy = A * *monodromy;
  }
  return J;
}

std::vector<Vec> MultipleShooting::orbit(const Vec& u, double p) const {
  const int n = f_.n, M = kSegments;
  std::vector<Vec> out;
  for (int j = 0; j < M; ++j) flowMap(f_, u.segment(j * n, n), u(M * n) / M, p, kStepsPerArc, &out);
  return out;
}

Vec MultipleShooting::sample(const std::function<Vec(double t)>& y, double T) const {
  const int n = f_.n, M = kSegments;
  Vec u(M * n + 1);
  for (int j = 0; j < M; ++j) u.segment(j * n, n) = y(j * T / M);
  u(M * n) = T;
  return u;
}

double MultipleShooting::margin(const Vec& u, double p) const {
  if (!f_.margin) return std::numeric_limits<double>::infinity();
  double m = std::numeric_limits<double>::infinity();
  for (const Vec& y : orbit(u, p)) m = std::min(m, f_.margin(y, p));
  return m;
}

}  // namespace metrosync::continuation
