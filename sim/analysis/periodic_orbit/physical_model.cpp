#include "sim/analysis/periodic_orbit/physical_model.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace metrosync::orbit {

PhysicalModel::PhysicalModel(const Rig& rig)
    : eq_(rig),
      law_(rig.platform.friction),
      normal_force_(rig.totalMass() * rig.gravity_m_s2),
      n_(eq_.numSwinging()),
      d_(2 * eq_.numSwinging() + 2),
      k_spring_(eq_.hasPlatform() ? rig.platform.spring_N_m : 0.0) {
  // the derivatives below have no air drag (issue 41): refused, not silently wrong
  if (const std::string key = rig.fullModelOnlyKey(); !key.empty())
    throw std::invalid_argument(key +
                                ": the periodic orbits' and the fit's derivatives have no air drag "
                                "(only `run`, `compare`, `sweep`, `basin` and `animate` take it)");
  pl_.n = n_;
  pl_.law_values = static_cast<int>(law_.values().size());
  p_ = Vec::Zero(pl_.size());
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& k = eq_.pendulum(j);
    p_(pl_.mL(j)) = k.mL;
    p_(pl_.mgL(j)) = k.mgL;
    p_(pl_.inertia(j)) = k.inertia;
    p_(pl_.damping(j)) = k.damping;
    p_(pl_.thetaC(j)) = k.theta_c;
    p_(pl_.impulse(j)) = k.impulse;
    const MetronomeSpec& m = rig.metronomes[k.rig_index];
    p_(pl_.start(theta(j))) = m.start_angle_rad;
    p_(pl_.start(omega(j))) = m.start_rate_rad_s;
  }
  p_(pl_.mass()) = eq_.totalMass();
  p_(pl_.spring()) = k_spring_;
  p_(pl_.normalForce()) = normal_force_;
  for (int i = 0; i < pl_.law_values; ++i) p_(pl_.lawValue(i)) = law_.values()[i];
  if (eq_.hasPlatform()) {  // a fixed platform's x and xdot stay 0 (the engine's start)
    p_(pl_.start(kX)) = rig.platform.start_x_m;
    p_(pl_.start(kV)) = rig.platform.start_v_m_s;
  }
  law_partials_ = frictionPartials(law_, normal_force_, 0.0, PlatformMode::Stuck, fp_);
  terms_.resize(n_);
  sums_.dG = sums_.dS = acc_.dy = Vec::Zero(d_);
  acc_.dp = Vec::Zero(pl_.size());
}

Vec PhysicalModel::rhs(const Vec& y, PlatformMode mode) const {
  std::vector<double> in(d_ + 2, 0.0), dy(d_ + 2, 0.0);  // + the engine's two quadratures
  for (int k = 0; k < d_; ++k) in[k] = y(k);
  eq_.rhs(in.data(), mode, dy.data());
  return Eigen::Map<const Vec>(dy.data(), d_);
}

void PhysicalModel::pendulumTerms(const double* y) const {
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& k = eq_.pendulum(j);
    PendulumTerms& t = terms_[j];
    t.s = std::sin(y[theta(j)]);
    t.co = std::cos(y[theta(j)]);
    t.w = y[omega(j)];
    t.c = k.mL * t.co;
    t.r = -k.mgL * t.s - k.damping * t.w;
    t.inv_I = k.inv_inertia;
  }
}

void PhysicalModel::platformSums(double x, PlatformSums& p) const {
  p.dG.setZero();
  p.dS.setZero();
  p.G = -k_spring_ * x;
  p.S = 0.0;
  p.dG(kX) = -k_spring_;
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& k = eq_.pendulum(j);
    const PendulumTerms& t = terms_[j];
    p.G += k.mL * t.s * t.w * t.w - t.c * t.r * t.inv_I;
    p.S += t.c * t.c * t.inv_I;
    // d/dtheta of mL s w^2 - c r / I with dc = -mL s, dr = -mgL co
    p.dG(theta(j)) = k.mL * t.co * t.w * t.w + (k.mL * t.s * t.r + t.c * k.mgL * t.co) * t.inv_I;
    p.dG(omega(j)) = 2 * k.mL * t.s * t.w + t.c * k.damping * t.inv_I;
    p.dS(theta(j)) = -2 * t.c * k.mL * t.s * t.inv_I;
  }
}

void PhysicalModel::addPlatformSumsParameters(double x, double wG, double wS, Vec& out) const {
  out(pl_.spring()) += -wG * x;
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& k = eq_.pendulum(j);
    const PendulumTerms& t = terms_[j];
    // G = sum (mL s w^2 - c r / I) - k x, S = sum c^2 / I, c = mL co, r = -mgL s - b w
    out(pl_.mL(j)) +=
        wG * (t.s * t.w * t.w - t.co * t.r * t.inv_I) + wS * 2 * k.mL * t.co * t.co * t.inv_I;
    out(pl_.mgL(j)) += wG * t.c * t.s * t.inv_I;
    out(pl_.inertia(j)) += (wG * t.c * t.r - wS * t.c * t.c) * t.inv_I * t.inv_I;
    out(pl_.damping(j)) += wG * t.c * t.w * t.inv_I;
  }
}

// Meff a = G + F, Meff = M - S: da = (dG + dF + a dS - a dM) / Meff, in y and in p (after
// pendulumTerms at y).
bool PhysicalModel::acceleration(const double* y, PlatformMode mode, Acceleration& acc) const {
  acc.dy.setZero();
  acc.dp.setZero();
  acc.a = 0.0;
  if (!eq_.hasPlatform() || (coulomb() && mode == PlatformMode::Stuck)) return false;
  platformSums(y[kX], sums_);
  const double v = y[kV];
  acc.meff = eq_.totalMass() - sums_.S;
  acc.a = (sums_.G + eq_.friction().force(v, mode)) / acc.meff;
  const bool law = law_partials_ && frictionPartials(law_, normal_force_, v, mode, fp_);
  acc.dy = (sums_.dG + acc.a * sums_.dS) / acc.meff;
  if (law) acc.dy(kV) += fp_.force_per_velocity / acc.meff;
  addPlatformSumsParameters(y[kX], 1.0 / acc.meff, acc.a / acc.meff, acc.dp);
  acc.dp(pl_.mass()) -= acc.a / acc.meff;
  if (!law) return true;
  acc.dp(pl_.normalForce()) += fp_.force_per_normal_force / acc.meff;
  for (int i = 0; i < pl_.law_values; ++i)
    acc.dp(pl_.lawValue(i)) += fp_.force_per_value[i] / acc.meff;
  return true;
}

// x' = v, v' = a, theta_j' = w_j, w_j' = (r_j - c_j a) / I_j, differentiated along each column q:
// the platform's row da . Y_q + dp . dirs_q, each pendulum's its own terms and -c_j / I_j times
// the platform's.
void PhysicalModel::variationalRates(const double* y, PlatformMode mode, const double* Yp,
                                     const double* dirs_p, int k, double* dYp) const {
  pendulumTerms(y);
  const bool moving = acceleration(y, mode, acc_);
  const double a = acc_.a;
  const int P = pl_.size();
  const Eigen::Map<const Mat> Y(Yp, d_, k);
  Eigen::Map<Mat> dY(dYp, d_, k);
  for (int q = 0; q < k; ++q) {
    double av = 0.0;
    if (moving) {
      av = acc_.dy.dot(Y.col(q));
      if (dirs_p) av += acc_.dp.dot(Eigen::Map<const Vec>(dirs_p + q * P, P));
    }
    dY(kX, q) = moving ? Y(kV, q) : 0.0;
    dY(kV, q) = av;
    for (int j = 0; j < n_; ++j) dY(omega(j), q) = -eq_.pendulum(j).mL * av;  // * co / I below
  }
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& kj = eq_.pendulum(j);
    const PendulumTerms& t = terms_[j];
    const double rate = (t.r - t.c * a) * t.inv_I;  // w_j'
    const double by_theta = (-kj.mgL * t.co + kj.mL * t.s * a) * t.inv_I;
    const double by_omega = -kj.damping * t.inv_I;
    for (int q = 0; q < k; ++q) {
      double dw =
          dY(omega(j), q) * t.co * t.inv_I + by_theta * Y(theta(j), q) + by_omega * Y(omega(j), q);
      if (dirs_p) {
        const double* dq = dirs_p + q * P;
        // w_j' through its own constants: -co a / I (mL), -s / I (mgL), -w_j' / I (I), -w / I
        dw += -t.co * a * t.inv_I * dq[pl_.mL(j)] - t.s * t.inv_I * dq[pl_.mgL(j)] -
              rate * t.inv_I * dq[pl_.inertia(j)] - t.w * t.inv_I * dq[pl_.damping(j)];
      }
      dY(theta(j), q) = Y(omega(j), q);
      dY(omega(j), q) = dw;
    }
  }
}

Mat PhysicalModel::jacobian(const Vec& y, PlatformMode mode) const {
  const Mat I = Mat::Identity(d_, d_);
  Mat J(d_, d_);
  variationalRates(y.data(), mode, I.data(), nullptr, d_, J.data());
  return J;
}

Mat PhysicalModel::parameterJacobian(const Vec& y, PlatformMode mode) const {
  const int P = pl_.size();
  const Mat zero = Mat::Zero(d_, P), I = Mat::Identity(P, P);
  Mat B(d_, P);
  variationalRates(y.data(), mode, zero.data(), I.data(), P, B.data());
  return B;
}

double PhysicalModel::holdingForce(const Vec& y) const {
  return eq_.holdingForce(y.data());
}

Vec PhysicalModel::holdingForceGradient(const Vec& y) const {
  pendulumTerms(y.data());
  platformSums(y(kX), sums_);
  Vec g = -sums_.dG;  // H = -G
  g(kV) = 0.0;
  return g;
}

Vec PhysicalModel::holdingForceParameters(const Vec& y) const {
  Vec out = Vec::Zero(pl_.size());
  pendulumTerms(y.data());
  addPlatformSumsParameters(y(kX), -1.0, 0.0, out);
  return out;
}

Vec PhysicalModel::staticBoundParameters() const {
  Vec out = Vec::Zero(pl_.size());
  if (!law_partials_ || !frictionPartials(law_, normal_force_, 0.0, PlatformMode::Stuck, fp_))
    return out;
  out(pl_.normalForce()) = fp_.static_bound_per_normal_force;
  for (int i = 0; i < pl_.law_values; ++i) out(pl_.lawValue(i)) = fp_.static_bound_per_value[i];
  return out;
}

PlatformMode PhysicalModel::modeAtRest(const Vec& y) const {
  return eq_.dryFriction().modeAtRest(holdingForce(y));
}

Vec PhysicalModel::tick(const Vec& y, const std::vector<int>& ticked) const {
  std::vector<double> out(y.data(), y.data() + d_), pins(n_, 0.0);
  for (int j : ticked) pins[j] = eq_.escapement(j).tickImpulse(out[theta(j)]);
  eq_.applyImpulse(out.data(), pins.data(), 0.0);
  return Eigen::Map<const Vec>(out.data(), d_);
}

// D of y + M(theta)^-1 p: the impulse is fixed, the mass matrix depends on the angles through
// c_j = m_j L_j cos theta_j. dv = -Q / Meff, Q = sum c_j p_j / I_j; dw_j = (p_j - c_j dv) / I_j.
Mat PhysicalModel::tickJacobian(const Vec& y, const std::vector<int>& ticked) const {
  Mat D = Mat::Identity(d_, d_);
  if (!eq_.hasPlatform()) return D;  // dw_j = p_j / I_j: no dependence on the state
  std::vector<double> p(n_, 0.0);
  for (int j : ticked) p[j] = eq_.escapement(j).tickImpulse(y(theta(j)));
  pendulumTerms(y.data());
  platformSums(y(kX), sums_);
  const PlatformSums& sums = sums_;
  const double meff = eq_.totalMass() - sums.S;
  double Q = 0.0;
  for (int j = 0; j < n_; ++j)
    Q += eq_.pendulum(j).mL * std::cos(y(theta(j))) * p[j] * eq_.pendulum(j).inv_inertia;
  const double dv = -Q / meff;
  for (int k = 0; k < n_; ++k) {
    const network::PendulumConstants& ck = eq_.pendulum(k);
    const double dQ = -ck.mL * std::sin(y(theta(k))) * p[k] * ck.inv_inertia;
    const double ddv = (-dQ + dv * sums.dS(theta(k))) / meff;
    D(kV, theta(k)) = ddv;
    for (int j = 0; j < n_; ++j) {
      const network::PendulumConstants& cj = eq_.pendulum(j);
      const double dc = j == k ? -cj.mL * std::sin(y(theta(j))) : 0.0;
      D(omega(j), theta(k)) = -(dc * dv + cj.mL * std::cos(y(theta(j))) * ddv) * cj.inv_inertia;
    }
  }
  return D;
}

// The same map at a fixed state, in p: the pins' impulses side_j J-bar_j, and M^-1 through
// M, m_j L_j and I_j: dv' = (-dQ - dv dMeff) / Meff, dw_j' = (dp_j - dc_j dv - c_j dv') / I_j +
// (p_j - c_j dv) d(1 / I_j).
Mat PhysicalModel::tickParameterJacobian(const Vec& y, const std::vector<int>& ticked) const {
  Mat D = Mat::Zero(d_, pl_.size());
  std::vector<double> pins(n_, 0.0);
  for (int j : ticked) pins[j] = eq_.escapement(j).tickImpulse(y(theta(j)));
  impulseParameterJacobian(y, pins, ticked, D);
  return D;
}

void PhysicalModel::impulseParameterJacobian(const Vec& y, const std::vector<double>& pins,
                                             const std::vector<int>& ticked, Mat& D) const {
  const int P = pl_.size();
  std::vector<double> c(n_), co(n_), side(n_, 0.0);
  for (int j : ticked) side[j] = pins[j] > 0 ? 1.0 : -1.0;
  double Q = 0.0, S = 0.0;
  Vec dQ = Vec::Zero(P), dMeff = Vec::Zero(P);
  dMeff(pl_.mass()) = 1.0;
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& k = eq_.pendulum(j);
    co[j] = std::cos(y(theta(j)));
    c[j] = k.mL * co[j];
    Q += c[j] * pins[j] * k.inv_inertia;
    S += c[j] * c[j] * k.inv_inertia;
    dQ(pl_.mL(j)) = co[j] * pins[j] * k.inv_inertia;
    dQ(pl_.inertia(j)) = -c[j] * pins[j] * k.inv_inertia * k.inv_inertia;
    dQ(pl_.impulse(j)) = c[j] * side[j] * k.inv_inertia;
    dMeff(pl_.mL(j)) = -2 * k.mL * co[j] * co[j] * k.inv_inertia;
    dMeff(pl_.inertia(j)) = c[j] * c[j] * k.inv_inertia * k.inv_inertia;
  }
  const bool platform = eq_.hasPlatform();
  const double meff = eq_.totalMass() - S, dv = platform ? -Q / meff : 0.0;
  const Vec ddv = platform ? Vec((-dQ - dv * dMeff) / meff) : Vec::Zero(P);
  D.row(kV) = ddv.transpose();
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& k = eq_.pendulum(j);
    D.row(omega(j)) = -c[j] * k.inv_inertia * ddv.transpose();
    D(omega(j), pl_.mL(j)) += -co[j] * dv * k.inv_inertia;
    D(omega(j), pl_.inertia(j)) += -(pins[j] - c[j] * dv) * k.inv_inertia * k.inv_inertia;
    D(omega(j), pl_.impulse(j)) += side[j] * k.inv_inertia;
  }
}

Vec PhysicalModel::plasticStop(const Vec& y) const {
  std::vector<double> out(y.data(), y.data() + d_);
  const std::vector<double> none(n_, 0.0);
  const double v = out[kV];
  if (v != 0) eq_.applyImpulse(out.data(), none.data(), -v / eq_.platformMobility(out.data()));
  Vec z = Eigen::Map<const Vec>(out.data(), d_);
  z(kV) = 0.0;  // held: the resolver's setMode(Stuck)
  return z;
}

// dv = -v (the impulse -v Meff on x), dw_j = c_j v / I_j.
Mat PhysicalModel::plasticStopJacobian(const Vec& y) const {
  Mat D = Mat::Identity(d_, d_);
  D(kV, kV) = 0.0;
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& c = eq_.pendulum(j);
    D(omega(j), kV) = c.mL * std::cos(y(theta(j))) * c.inv_inertia;
    D(omega(j), theta(j)) += -c.mL * std::sin(y(theta(j))) * y(kV) * c.inv_inertia;
  }
  return D;
}

Mat PhysicalModel::plasticStopParameterJacobian(const Vec& y) const {
  Mat D = Mat::Zero(d_, pl_.size());
  const double v = y(kV);
  for (int j = 0; j < n_; ++j) {
    const network::PendulumConstants& c = eq_.pendulum(j);
    const double co = std::cos(y(theta(j)));
    D(omega(j), pl_.mL(j)) = co * v * c.inv_inertia;
    D(omega(j), pl_.inertia(j)) = -c.mL * co * v * c.inv_inertia * c.inv_inertia;
  }
  return D;
}

Vec PhysicalModel::stateFromRow(const std::vector<double>& row) const {
  Vec y(d_);
  y(kX) = row[1];
  y(kV) = row[2];
  for (int j = 0; j < n_; ++j) {
    y(theta(j)) = row[3 + 2 * rigIndex(j)];
    y(omega(j)) = row[4 + 2 * rigIndex(j)];
  }
  return y;
}

}  // namespace metrosync::orbit
