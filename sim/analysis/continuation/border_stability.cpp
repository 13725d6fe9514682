#include "sim/analysis/continuation/border_stability.h"

#include <algorithm>
#include <cmath>

#include "base/constants.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// The displacement off the state: far above the state's accuracy (1e-12) and the integrator's
// (1e-10), small enough for the local dynamics.
constexpr double kOffset = 1e-3;
// How long each run is, in slow time: ~10 times the slowest relaxation of the shipped rigs'
// locked states (rates >= 0.05), so that a stable state is approached well within it.
constexpr double kRunTau = 200.0;
// Back towards the state: the final distance below this fraction of the displacement.
constexpr double kReturned = 0.5;

double wrapped(double d) {
  return std::remainder(d, kTwoPi);
}

// max |A_i - A_i*|, |psi_j - psi_j*| at the end of a run from z0.
double endDistance(ScaledParams sp, const std::vector<Cd>& z0, const std::vector<double>& A,
                   const std::vector<double>& psi) {
  for (size_t i = 0; i < z0.size(); ++i)
    sp.thetadot0[i] = z0[i].real(), sp.theta0[i] = z0[i].imag();
  SlowFlowOptions opt;
  opt.tau_end = kRunTau;
  MemorySink sink;
  const RunReport rep = runSlowFlow(sp, opt, sink);
  const EnvelopeRow& last = rep.final_row;
  if (last.A.size() != A.size()) return std::numeric_limits<double>::infinity();
  double d = 0;
  for (size_t i = 0; i < A.size(); ++i) d = std::max(d, std::abs(last.A[i] - A[i]));
  for (size_t j = 0; j < psi.size(); ++j) d = std::max(d, std::abs(wrapped(last.psi[j] - psi[j])));
  return d;
}

}  // namespace

bool slowFlowReturns(const ScaledParams& sp, const std::vector<Cd>& z) {
  std::vector<double> A, psi;
  for (const Cd& zi : z) A.push_back(std::abs(zi));
  for (size_t j = 1; j < z.size(); ++j) psi.push_back(std::arg(z[0]) - std::arg(z[j]));
  const std::vector<std::vector<Cd>> starts = [&] {
    std::vector<Cd> up = z, down = z, turned = z;
    for (size_t i = 0; i < z.size(); ++i) {
      up[i] *= 1 + kOffset, down[i] *= 1 - kOffset;
      if (i > 0) turned[i] *= std::polar(1.0, kOffset);
    }
    return std::vector<std::vector<Cd>>{up, down, turned};
  }();
  return std::all_of(starts.begin(), starts.end(), [&](const std::vector<Cd>& z0) {
    return endDistance(sp, z0, A, psi) <
           kReturned * kOffset * std::max(1.0, *std::max_element(A.begin(), A.end()));
  });
}

}  // namespace metrosync::continuation
