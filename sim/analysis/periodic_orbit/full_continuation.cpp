#include "sim/analysis/periodic_orbit/full_continuation.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/analysis/periodic_orbit/orbit_continuation.h"
#include "sim/engines/direct/direct_engine.h"

namespace metrosync::orbit {

namespace {

// Below this scaled amplitude every pendulum has stopped: oscillator death, no orbit to follow
// (a swinging metronome has A ~ 1; a dying one decays exponentially to ~1e-10 over a run).
constexpr double kStopped = 1e-3;
// The section is looked for within this many fast periods (2 pi) from the run's end.
constexpr double kSearchPeriods = 3.0;
// A run has settled when its state on the section comes back within this (scaled) after one
// period: a locked state reaches it geometrically (1e-3 is its multiplier^n with n in the
// hundreds even at 0.98), a drift moves the section state by O(epsilon A) ~ 0.1 per period.
// Newton then takes the state the rest of the way, to the orbit the run is settling onto.
constexpr double kSettled = 1e-3;

// The rig run from its start for `factor` times its duration: the final state, scaled.
Vec runEnd(const Rig& rig, const ScaledModel& model, double factor) {
  Rig r = rig;
  r.sim.t_end_s *= factor;
  r.sim.sample_s = r.sim.t_end_s;
  FinalStateSink none;
  const RunReport rep = runDirectModel(r, none);
  if (!rep.complete) throw NoOrbit("the run of the rig's start failed: " + rep.failure);
  return model.stateFromRow(rep.final_trajectory_row);
}

int largestPendulum(const ScaledModel& m, const Vec& z) {
  int r = 0;
  for (int j = 1; j < m.n(); ++j)
    if (std::hypot(z(m.theta(j)), z(m.omega(j))) > std::hypot(z(m.theta(r)), z(m.omega(r)))) r = j;
  return r;
}

}  // namespace

SettledOrbit settleOrbit(const Rig& rig, const ReturnSettings& ret, const NewtonSettings& newton) {
  const ScaledModel model(rig);
  if (model.n() == 0) throw NoOrbit("every metronome is locked: nothing swings");
  std::string why;
  for (double factor : {1.0, 3.0, 10.0}) {
    const Vec z = runEnd(rig, model, factor);
    const int r = largestPendulum(model, z);
    const double amplitude = std::hypot(z(model.theta(r)), z(model.omega(r)));
    const double t_end = model.scaled().tau_end / model.scaled().epsilon * factor;
    if (amplitude < kStopped)
      throw NoOrbit("every metronome has stopped by t = " + numberText(t_end, 6) +
                    " (scaled; largest amplitude " + numberText(amplitude, 6) +
                    "): no periodic orbit");
    const ReturnMap map(rig, r, ret);
    try {
      const Pass first = map.firstCrossing(z, kSearchPeriods * kTwoPi);
      const Pass again = map.pass(first.u1, kTwoPi, false);
      const double moves = (again.u1 - again.u0).lpNorm<Eigen::Infinity>();
      if (moves > kSettled) {
        why = "at t = " + numberText(t_end, 6) +
              " (scaled) its state on the section still moves by " + numberText(moves, 6) +
              " in one period";
        continue;
      }
      if (auto o = shoot(map, first.u1, again.period, newton, &why))
        return {*o, r,
                "the rig's start run to t = " + numberText(t_end, 6) +
                    " (scaled), then Newton in " + std::to_string(o->iterations) +
                    " iterations (residual " + numberText(o->residual, 6) + ")"};
    } catch (const std::exception& e) {  // OrbitFailure, or a piece that cannot be integrated
      why = e.what();
    }
  }
  throw NoOrbit(
      "the rig's start does not settle onto a periodic orbit (full model, run to 10 "
      "times its duration): " +
      why);
}

FullContinuation continueFull(const std::function<Rig(double)>& rig_at, const std::string& param,
                              double from, double to, const FamilySettings& settings) {
  const auto wall0 = std::chrono::steady_clock::now();
  OrbitProblem prob;
  prob.rig_at = rig_at;
  const Rig rig = rig_at(from);
  const SettledOrbit start = settleOrbit(rig, prob.ret, prob.newton);
  prob.pendulum = start.pendulum;
  FullContinuation out;
  out.param = param;
  out.from = from;
  out.to = to;
  out.start = start.how;
  out.metronomes = static_cast<int>(rig.metronomes.size());
  const ReturnMap map(rig, start.pendulum, prob.ret);
  for (int k = 0; k < map.section().dim(); ++k) out.section.push_back(map.section().name(k));
  out.section_name =
      "theta_" + std::to_string(map.model().rigIndex(start.pendulum) + 1) + " = 0, rising";
  out.families.push_back(continueFamily(prob, start.orbit, from, settings));
  const Family main = out.families.front();
  for (const OrbitBifurcation& b : main.special) {
    if (b.type != "branch" || main.symmetry == SymmetryKind::None ||
        static_cast<int>(out.families.size()) > kMaxSwitches)
      continue;
    if (auto f = switchBranch(prob, main.symmetry, b.point, settings))
      out.families.push_back(std::move(*f));
  }
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace metrosync::orbit
