// `metrosync continue --model full` as an analysis: the rig's own start run by the engine until it
// settles onto a locked state, the state corrected to a periodic orbit by shooting, and its family
// followed in one rig key (orbit_continuation.h). The files are written by
// tools/report/full_continuation_report.h.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/analysis/periodic_orbit/family.h"

namespace metrosync::orbit {

// The rig's start does not settle onto a periodic orbit (drift, death, a run that fails): bad
// input for the command (exit 2), with the reason.
struct NoOrbit : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SettledOrbit {
  Orbit orbit;
  int pendulum = 0;  // the section's (the largest amplitude at the run's end)
  std::string how;   // "the rig's start run to t = ..., Newton in 3 iterations"
};

// The periodic orbit the rig's start settles to: the run to the rig's end (then 3 and 10 times
// longer) put on the section of its largest pendulum, and Newton from there. Throws NoOrbit.
SettledOrbit settleOrbit(const Rig& rig, const ReturnSettings& ret, const NewtonSettings& newton);

struct FullContinuation {
  std::string param;
  double from = 0.0, to = 0.0;
  std::string start;                 // how the start orbit was found
  int metronomes = 0;                // N, the rig's
  std::vector<std::string> section;  // the section coordinates' names ("xdot", "theta_2", ...)
  std::string section_name;          // "theta_1 = 0, rising"
  // the family of the start (first), then the asymmetric families switched onto at its
  // symmetry-breaking branch points (orbit_continuation.h switchBranch)
  std::vector<Family> families;
  double wall_seconds = 0.0;
};

// The family through the orbit that rig_at(from)'s start settles to, over [from, to], and the
// asymmetric families branching off it (at most kMaxSwitches). Throws NoOrbit for a start that
// does not settle.
constexpr int kMaxSwitches = 2;
FullContinuation continueFull(const std::function<Rig(double)>& rig_at, const std::string& param,
                              double from, double to, const FamilySettings& settings);

}  // namespace metrosync::orbit
