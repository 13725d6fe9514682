#include "sim/analysis/periodic_orbit/orbit_measures.h"

#include <cmath>
#include <complex>

#include "base/constants.h"
#include "sim/analysis/periodic_orbit/piece_flow.h"

namespace metrosync::orbit {

namespace {

// 8-point Gauss-Legendre on [-1, 1] (Abramowitz and Stegun 25.4.30): exact for polynomials of
// degree 15; on sub-intervals of at most kSubInterval of a smooth piece (the fast period is 2 pi)
// the averages are exact to ~1e-12.
constexpr int kNodes = 8;
constexpr double kNode[kNodes] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                  -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                  0.7966664774136267,  0.9602898564975363};
constexpr double kWeight[kNodes] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                    0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                    0.2223810344533745, 0.1012285362903763};
constexpr double kSubInterval = 0.5;

// Accumulates the integrands at one state: A_i, and e^{i (phi_1 - phi_j)} (t cancels).
struct Sums {
  std::vector<double> A;
  std::vector<std::complex<double>> rot;
  void add(const ScaledModel& m, const Vec& z, double w) {
    std::vector<double> phase(m.n());
    for (int j = 0; j < m.n(); ++j) {
      const double th = z(m.theta(j)), om = z(m.omega(j));
      A[j] += w * std::hypot(th, om);
      phase[j] = std::atan2(th, om);
    }
    for (int j = 1; j < m.n(); ++j) rot[j] += w * std::polar(1.0, phase[0] - phase[j]);
  }
};

void integratePiece(PieceFlow& flow, FlowPoint& at, double t_end, PlatformMode mode,
                    const ScaledModel& m, Sums& sums) {
  const double t0 = at.t, len = t_end - t0;
  if (!(len > 0)) return;
  const int parts = static_cast<int>(std::ceil(len / kSubInterval));
  const double half = 0.5 * len / parts;
  for (int q = 0; q < parts; ++q) {
    const double mid = t0 + (2 * q + 1) * half;
    for (int k = 0; k < kNodes; ++k) {
      flow.advance(at, mid + half * kNode[k], mode);
      sums.add(m, at.z, half * kWeight[k]);
    }
  }
  flow.advance(at, t_end, mode);
}

}  // namespace

EventCounts countEvents(const ReturnMap& map, const Pass& pass) {
  const ScaledModel& m = map.model();
  EventCounts c;
  c.ticks.assign(map.rig().metronomes.size(), 0);
  for (const EngineWindow& w : pass.windows) {
    for (int j : w.ticked) ++c.ticks[m.rigIndex(j)];
    if (w.mode_before == w.mode_after || !m.coulomb()) continue;
    if (!w.ticked.empty())
      ++c.at_ticks;
    else if (w.mode_before == PlatformMode::Stuck || w.mode_after == PlatformMode::Stuck)
      ++c.stick_slip;
    else
      ++c.reversals;
  }
  return c;
}

OrbitMeasures measureOrbit(const ReturnMap& map, const Orbit& orbit) {
  const ScaledModel& m = map.model();
  const Pass& p = orbit.pass;
  Sums sums{std::vector<double>(m.n(), 0.0), std::vector<std::complex<double>>(m.n())};
  PieceFlow flow(m, map.settings().accuracy);
  FlowPoint at{0.0, p.z0, Mat()};
  PlatformMode mode = p.start_mode;
  for (const EngineWindow& w : p.windows) {
    integratePiece(flow, at, w.t, mode, m, sums);
    at.z = w.after;
    mode = w.mode_after;
  }
  integratePiece(flow, at, p.period, mode, m, sums);
  OrbitMeasures out;
  const int N = static_cast<int>(map.rig().metronomes.size());
  out.A.assign(N, 0.0);
  for (int j = 0; j < m.n(); ++j) out.A[m.rigIndex(j)] = sums.A[j] / p.period;
  out.psi.assign(N > 0 ? N - 1 : 0, std::nan(""));
  // psi_j = phi_1 - phi_j with metronome 1 the first swinging one, in [-pi/2, 3 pi/2) (as the
  // slow flow's branches.csv)
  for (int j = 1; j < m.n(); ++j) {
    double psi = std::arg(sums.rot[j]);
    if (psi < -kPi / 2) psi += 2 * kPi;
    out.psi[m.rigIndex(j) - 1] = psi;
  }
  out.events = countEvents(map, p);
  return out;
}

}  // namespace metrosync::orbit
