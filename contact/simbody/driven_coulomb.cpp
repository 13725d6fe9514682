#include "contact/simbody/driven_coulomb.h"

#include <Simbody.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "base/constants.h"
#include "contact/simbody/driven_coulomb_harness.h"

namespace metrosync {

namespace {

using namespace SimTK;
using Harness = DrivenCoulombHarness;

// A stuck platform changes nothing the integrator's error control sees, so its steps grow; but
// for B > 1 the stick margin 1 - |B sin t| is negative on windows of width pi - 2 asin(1/B)
// (tiny as B -> 1+), and a step that straddles a whole window sees the same sign at both ends
// and misses the slip. A quarter of the window keeps every window resolved.
double maxStepFor(double B) {
  double h = 0.1;
  if (B > 1) h = std::min(h, 0.25 * (kPi - 2 * std::asin(1 / B)));
  return h;
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from the Chebyshev guesses).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = -z;
    x[n - 1 - i] = z;
    w[i] = w[n - 1 - i] = 2 / ((1 - z * z) * dp * dp);
  }
}

// Period m of the switch sequence (switches per drive period) if its last 2 m entries repeat
// with a shift of 2 pi (same modes, instants to within tol); 0 otherwise. Also the mismatch.
int periodicity(const std::vector<DrivenCoulombSwitch>& s, double tol, double& mismatch) {
  const int n = static_cast<int>(s.size());
  for (int m = 1; 2 * m <= n && m <= 8; ++m) {
    double worst = 0.0;
    bool same = true;
    for (int j = n - m; j < n && same; ++j) {
      same = s[j].mode == s[j - m].mode;
      worst = std::max(worst, std::abs(s[j].t - s[j - m].t - kTwoPi));
    }
    if (same && worst <= tol) {
      mismatch = worst;
      return m;
    }
  }
  return 0;
}

// One run of the driven element from rest at t = 0 (B sin 0 = 0: stuck), with Simbody's
// Runge-Kutta-Merson at the measurement's accuracy.
struct DrivenRun {
  DrivenRun(double B, const DrivenCoulombOptions& opt) : h(B), integ(h.system) {
    State s = h.system.getDefaultState();
    h.settleAtRest(s);
    integ.setAccuracy(opt.accuracy);
    integ.setMaximumStepSize(maxStepFor(B));
    ts = std::make_unique<TimeStepper>(h.system, integ);
    ts->initialize(s);
  }
  Harness h;
  RungeKuttaMersonIntegrator integ;
  std::unique_ptr<TimeStepper> ts;
};

// The measured period: pass 1 runs from rest one drive period at a time until the switch
// instants repeat (or the platform stays still for a whole period), and returns the start of each
// smooth piece of that period, filling r's periodicity fields and t_end.
std::vector<DrivenCoulombSwitch> measuredPeriod(double B, const DrivenCoulombOptions& opt,
                                                DrivenCoulombMeasurement& r, double& t_end) {
  DrivenRun run(B, opt);
  for (int k = 1; k <= opt.max_periods; ++k) {
    run.ts->stepTo(kTwoPi * k);
    const auto& sw = run.h.switches();
    // never moved since a whole period, or a whole period stopped since the last switch
    const bool still =
        sw.empty() ? k >= 2 : sw.back().mode == 0 && kTwoPi * k - sw.back().t > kTwoPi;
    if (still) {
      r.periodic = true;
      r.periods = k - 1;
      r.t_start = kTwoPi * (k - 1);
      t_end = kTwoPi * k;
      return {{r.t_start, 0}};
    }
    double mismatch = 0.0;
    const int m = sw.empty() ? 0 : periodicity(sw, opt.periodic_tol, mismatch);
    if (m > 0) {
      const size_t first = sw.size() - m;  // the measured period starts at this switch
      r.periodic = true;
      r.period_mismatch = mismatch;
      r.periods = k - 1;
      r.t_start = sw[first].t;
      t_end = r.t_start + kTwoPi;
      r.switches.assign(sw.begin() + first, sw.end());
      return r.switches;
    }
  }
  return {};
}

// Pass 2: the same run again (deterministic), stopping at the Gauss nodes of every smooth piece
// of the measured period to read the element's acceleration y''; returns the integrals of
// y'' sin t and y'' cos t over the period.
std::pair<double, double> driveIntegrals(double B, const DrivenCoulombOptions& opt,
                                         const std::vector<DrivenCoulombSwitch>& pieces,
                                         double t_end) {
  std::vector<double> gx, gw;
  gaussLegendre(opt.gauss_nodes, gx, gw);
  double s_sin = 0.0, s_cos = 0.0;
  DrivenRun run(B, opt);
  for (size_t j = 0; j < pieces.size(); ++j) {
    const double lo = pieces[j].t, hi = j + 1 < pieces.size() ? pieces[j + 1].t : t_end;
    const double half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
    // a piece this short contributes at most (B + 1) 1e-13 / (2 pi B) to either beta
    if (!(half > 5e-14)) continue;
    for (int g = 0; g < opt.gauss_nodes; ++g) {
      const double t = mid + half * gx[g];
      run.ts->stepTo(t);
      State st = run.ts->getState();
      run.h.system.realize(st, Stage::Acceleration);
      const double ydd = run.h.slider.getOneUDot(st, MobilizerUIndex(0));
      s_sin += half * gw[g] * ydd * std::sin(t);
      s_cos += half * gw[g] * ydd * std::cos(t);
    }
  }
  return {s_sin, s_cos};
}

}  // namespace

DrivenCoulombMeasurement measureDrivenCoulomb(double B, const DrivenCoulombOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  if (!(B > 0) || !std::isfinite(B))
    throw std::invalid_argument("measureDrivenCoulomb: B must be finite and > 0");
  DrivenCoulombMeasurement r;
  r.B = B;
  double t_end = 0.0;
  const std::vector<DrivenCoulombSwitch> pieces = measuredPeriod(B, opt, r, t_end);
  if (r.periodic) {
    const auto [s_sin, s_cos] = driveIntegrals(B, opt, pieces, t_end);
    r.beta1 = s_sin / (kTwoPi * B);
    r.beta2 = s_cos / (kTwoPi * B);
  } else {
    r.beta1 = r.beta2 = std::nan("");
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

}  // namespace metrosync
