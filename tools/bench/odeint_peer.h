// The benchmark's hand-written C++ peer: the full model (e1.1a-c, N metronomes) integrated with
// Boost.Odeint the way a careful user would write it, so that metrosync's direct engine can be
// compared with the integrator a demanding user would actually build (issue 11).
//
//   variables   x, xdot, theta_j, thetadot_j in the paper's scaled units (s2.1: angles in units
//               of sqrt(eps), the platform in I1 eps^{3/2} / (m1 L1), time t = omega0 t-bar), so
//               that one absolute and one relative tolerance fit every component; the forces are
//               the physical ones of e1.1a-c (the Schur complement of the pendulums' inertias
//               gives xddot first, then each thetaddot_j)
//   steppers    "dopri5": runge_kutta_dopri5, controlled, with dense output; events are located
//               by Illinois root finding on the dense-output interpolant (calc_state)
//               "rkf78":  runge_kutta_fehlberg78, controlled, no interpolant; events are located
//               by root finding on exact steps (re-stepping from the step's start to each trial
//               time), and while the envelope is recorded every step ends on the next sample
//   events      a tick when |theta_j| passes theta_c,j outwards (the impulse J-bar_j through the
//               full mass matrix, platform free, every tick of the instant together), then the
//               platform's Coulomb rule: stuck while the holding force fits in mu-bar M g, else
//               slipping against the motion until xdot comes back to 0; viscous and no friction
//               have no platform events; a fixed platform takes no impulse
//   recording   the project's EnvelopeRecorder, fed 64 samples per fast period and the states on
//               both sides of every event (the direct engine's schedule, so that the envelopes
//               compare sample for sample); the first and last trajectory rows; no files. A sink
//               that declines the envelope (RunSink::wantsEnvelope false) gets no samples taken:
//               rkf78 then steps as its tolerance allows instead of ending every step on the
//               next sample (with samples its steps are at most T/64 long, so that its error and
//               cost hardly depend on the tolerance)
//
// Counts: steps = accepted steps, rhs_evals = right-hand-side evaluations of every kind (failed
// steps, root finding, re-steps), escapements per metronome, stick-slip switches, event windows.
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "sim/record/run_report.h"

namespace metrosync::bench {

struct OdeintOptions {
  std::string stepper = "dopri5";  // one of odeintIntegratorNames()
  double tolerance = 1e-8;         // odeint's absolute and relative error bound (scaled units)
};

// True when this binary was built with Boost.Odeint (CMake found Boost's headers).
bool odeintAvailable();
// The peer's steppers: dopri5, rkf78 (empty when not built).
std::vector<std::string> odeintIntegratorNames();

// Runs the rig to rig.sim.t_end_s. Never throws for a failed simulation (complete = false and
// why); throws std::invalid_argument for an unknown stepper; exceptions of `sink` propagate.
RunReport runOdeintPeer(const Rig& rig, RunSink& sink, const OdeintOptions& options);

}  // namespace metrosync::bench
