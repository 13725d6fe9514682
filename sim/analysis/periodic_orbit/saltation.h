// The saltation matrix of an event window: how a perturbation of the state just before the window
// maps to one just after it, the event's time moving with the perturbation (Aizerman and
// Gantmacher 1958; Leine and Nijmeijer, "Dynamics and bifurcations of non-smooth mechanical
// systems", 2004, ch. 3):
//     S = Dg + (f+ - Dg f-) dh^T / (dh . f-)
// g the jump map at the event, h the event function (rising through zero), f- and f+ the vector
// fields before and after (in their platform modes). For this model:
//   tick of pendulum j    h = side theta_j - theta_c, g the impulse through M(theta)^-1 (then a
//                         plastic stop when the engine stopped a micro-slip at once)
//   slip stops / reverses h = -mode xdot, g the identity (xdot is 0 there)
//   stuck breaks free     h = |H| - bound, H the holding force; g the identity (f+ = f- there:
//                         the slip starts with zero acceleration, so S = I to rounding)
// Simultaneous ticks (identical metronomes in phase) are taken one after the other, in index
// order, with no time in between: the product of their saltations.
//
// With the rig's parameters p (physical_model.h) the state after the window moves by
//     dy+ = S dy- + Sp dp,  Sp = Dg_p + (f+ - Dg f-) h_p^T / (dh . f-)
// h_p the event function's derivative in p at a fixed state (a tick: -d theta_c; a break-free:
// d|H| - d(static bound)), Dg_p the jump map's (an impulse's size, the masses it goes through).
// Computed in physical units; the scaled model's saltation is D^-1 S D.
#pragma once

#include "sim/analysis/periodic_orbit/engine_trace.h"
#include "sim/analysis/periodic_orbit/physical_model.h"
#include "sim/analysis/periodic_orbit/scaled_model.h"

namespace metrosync::orbit {

// A window in physical units (its states SI): the state the jump maps compute from
// window.before, S (d x d) and, when asked for, Sp (d x P; else empty).
struct WindowJump {
  Vec after;
  Mat S, Sp;
};
WindowJump windowJump(const PhysicalModel& model, const EngineWindow& window, bool with_parameters);

// A window of the scaled model (its states scaled): S of the scaled state.
Mat saltation(const ScaledModel& model, const EngineWindow& window);

// The state after `window` as the jump maps above compute it from window.before (for the check
// against the engine's own window.after).
Vec jumpedState(const ScaledModel& model, const EngineWindow& window);

}  // namespace metrosync::orbit
