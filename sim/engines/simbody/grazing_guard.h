// The Simbody engine's grazing guard (sim/engines/simbody/platform_run.h): a witness that touches
// zero or crosses twice within one step is invisible to Simbody's event location (a step whose
// end points both lie inside +-theta_c, or both on one side of a zero slip velocity, can still
// have crossed twice). The cubic Hermite through the step's end values finds such steps; the run
// then redoes the step with smaller steps.
#pragma once

#include <vector>

#include "contact/escapement.h"
#include "contact/platform_mode.h"

namespace metrosync {

// The state at the end of a step, as the guard needs it.
struct StepEnd {
  double t = 0;
  std::vector<double> th, w;  // (swinging pendulums) angle and rate
  std::vector<double> v, a;   // (platforms) slip velocity and acceleration of a Coulomb contact
};

// Cubic Hermite on [0, h] through (p0, d0), (p1, d1): its extreme value strictly inside the
// step (the largest interior maximum for want_max, else the smallest interior minimum), or NaN
// when it has none there.
double hermiteInteriorExtreme(double p0, double d0, double p1, double d1, double h, bool want_max);

// A tick witness of pendulum j (escapement esc, active) that may have crossed twice unseen
// between a and b.
bool tickGrazed(const StepEnd& a, const StepEnd& b, int j, const Escapement& esc);

// A slip of contact p in `mode` (not Stuck) that ended inside the step (it started from rest,
// where Simbody reports no transition away from zero; a step that ends on an event has crossed
// zero by design), or whose speed dipped close to zero inside it.
bool slipGrazed(const StepEnd& a, const StepEnd& b, int p, PlatformMode mode, bool event_step);

}  // namespace metrosync
