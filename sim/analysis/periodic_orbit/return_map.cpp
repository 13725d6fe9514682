#include "sim/analysis/periodic_orbit/return_map.h"

#include <algorithm>

#include "base/number_text.h"
#include "sim/analysis/periodic_orbit/piece_flow.h"
#include "sim/analysis/periodic_orbit/saltation.h"

namespace metrosync::orbit {

ReturnMap::ReturnMap(const Rig& rig, int pendulum, const ReturnSettings& settings)
    : rig_(rig), model_(rig), section_(model_, pendulum), settings_(settings) {}

Pass ReturnMap::pass(const Vec& u, double period_guess, bool with_jacobian) const {
  return around(section_.stateOf(u), settings_.reach * period_guess,
                settings_.min_fraction * period_guess, with_jacobian);
}

Pass ReturnMap::firstCrossing(const Vec& z, double reach) const {
  return around(z, reach, 0.0, false);
}

Pass ReturnMap::around(const Vec& z0, double t_end, double t_min, bool with_jacobian) const {
  const EngineTrace trace = traceFrom(rig_, model_, z0, t_end, settings_.accuracy);
  if (!trace.complete) throw OrbitFailure("the engine failed: " + trace.failure);
  Pass p;
  p.z0 = z0;
  p.u0 = section_.coordinatesOf(z0);
  p.start_mode = trace.start_mode;
  PieceFlow flow(model_, settings_.accuracy);
  FlowPoint at{0.0, z0, Mat()};
  const int d = model_.dim();
  const bool held = model_.coulomb() && trace.start_mode == PlatformMode::Stuck;
  if (with_jacobian) at.phi = held ? model_.plasticStopJacobian(z0) : Mat::Identity(d, d);
  PlatformMode mode = trace.start_mode;
  const SectionSpec section{section_.pendulum(), t_min};
  bool back = false;
  for (const EngineWindow& w : trace.windows) {
    if ((back = flow.advanceToSection(at, w.t, mode, section))) break;
    p.mismatch = std::max(p.mismatch, (at.z - w.before).lpNorm<Eigen::Infinity>());
    if (with_jacobian) at.phi = saltation(model_, w) * at.phi;
    at.z = w.after;
    mode = w.mode_after;
    p.windows.push_back(w);
  }
  if (!back) back = flow.advanceToSection(at, t_end, mode, section);
  if (!back)
    throw OrbitFailure("pendulum " + std::to_string(model_.rigIndex(section_.pendulum()) + 1) +
                       " does not come back to theta = 0 (rising) within t = " + numberText(t_end) +
                       " (scaled)");
  p.z1 = at.z;
  p.u1 = section_.coordinatesOf(at.z);
  p.period = at.t;
  p.end_mode = mode;
  if (with_jacobian) {
    p.phi = at.phi;
    p.jacobian = section_.reduce(at.phi, model_.rhs(at.z, mode));
  }
  return p;
}

}  // namespace metrosync::orbit
