// The benchmark's peer: the full model (e1.1a-c) in Siconos, as Siconos would naturally do it -
// Moreau-Jean time-stepping with the platform's Coulomb friction as a relay - so that metrosync's
// event-driven engines can be compared with a time-stepping scheme at equal error.
//
//   dynamical system  one LagrangianDS, q = (x, theta_1..theta_N): M(q) v' + F_int(q, v) = F_ext +
//   p
//                     (mass matrix, gravity, pivot damping and the pendulums' centripetal pull on
//                     the platform as plugins with their Jacobians; Moreau-Jean's Newton loop
//                     solves the nonlinear step)
//   friction          LagrangianLinearTIR y = xdot with a RelayNSL: lambda in [-B, B], -y in the
//                     normal cone (stuck: xdot = 0 and |lambda| <= B; slipping: lambda = -B sign
//                     xdot). lambda is an impulse per step, so B = mu-bar M g h
//   escapement        at the end of each step, a pendulum that has crossed +-theta_c outwards in
//                     that step gets its tick as a generalized force J-bar / h on theta_i during
//                     the next step (Moreau-Jean integrates it to the impulse J-bar; the relay's
//                     bound is O(h), so dry friction gives no impulse in the limit, as in the
//                     model)
//   recording         envelope samples at every step end and, by linear interpolation, at every
//                     fast-period boundary, into the project's EnvelopeRecorder
//
// Everything is first order in h: ticks land up to one step late, stick-slip switches are resolved
// at step ends. The report has the same fields as the engines' (steps, ticks, stick-slip switches;
// rhs_evals = evaluations of F_int, one per Newton iteration and step).
#pragma once

#include <string>

#include "models/rig.h"
#include "sim/record/run_report.h"

namespace metrosync::bench {

struct SiconosOptions {
  double step_s = 1e-3;       // Moreau-Jean step h
  double theta = 0.5;         // Moreau-Jean theta (0.5: the usual choice for mechanics)
  double newton_tol = 1e-10;  // Siconos's Newton tolerance per step
  unsigned newton_max = 50;   // Newton iterations per step at most
};

// True when this binary was built with Siconos (CMake found libsiconos-kernel-dev).
bool siconosAvailable();

// Why the peer cannot run `rig` faithfully ("" when it can): it covers Coulomb friction (mu >= 0),
// swinging pendulums with escapements, no platform spring, no locked metronomes, and physical or
// scaled rigs (both are held in SI).
std::string siconosUnsupported(const Rig& rig);

// Runs the rig to rig.sim.t_end_s. Like the engines, never throws for a failed simulation (the
// report says complete = false and why); exceptions thrown by `sink` propagate.
RunReport runSiconosPeer(const Rig& rig, RunSink& sink, const SiconosOptions& options);

}  // namespace metrosync::bench
