// The special points of a family of periodic orbits: the test functions watched along it (a sign
// change between two points means a zero in between), and what a located zero is.
//   fold            the parameter component of the tangent: the family turns back (a multiplier
//                   crosses +1); on the asymmetric orbits of two identical metronomes, a fold
//                   that lands on a symmetric orbit is where they branch off it: `branch`
//   branch          det [dF/du dF/dp; tangent^T]: another family crosses; on a symmetric family
//                   (symmetry.h) det C^T (dP/du - I) C: an antisymmetric multiplier crosses +1,
//                   asymmetric orbits branch off (symmetry breaking)
//   period-doubling prod_i (mu_i + 1): a real multiplier crosses -1
//   torus           Re prod_{i<j} (mu_i mu_j - 1): a complex pair crosses the unit circle
//                   (Neimark-Sacker; the full model's counterpart of the slow flow's Hopf: the
//                   amplitudes start to modulate); a real pair with mu_i mu_j = 1 (a neutral
//                   saddle) zeroes it too and is dropped
// The non-smooth ones change the events of a period (EventCounts) instead:
//   grazing         a pendulum stops (or starts) reaching theta_c: its ticks per period change
//   sliding         a stick phase appears or vanishes: the platform's switches per period change
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/periodic_orbit/family_map.h"
#include "sim/analysis/periodic_orbit/symmetry.h"

namespace metrosync::orbit {

enum class TestKind { Fold, Branch, PeriodDoubling, Torus };
const std::vector<TestKind>& testKinds();

double testFunction(TestKind kind, const FamilyMap& fm, const FamilyPoint& q);

// The located zero of `kind` at q, between a and b (the points around it) on a family of
// `symmetry`; nullopt when it is not that bifurcation (a neutral saddle).
std::optional<OrbitBifurcation> classify(TestKind kind, const FamilyPoint& q, const FamilyPoint& a,
                                         const FamilyPoint& b, const ScaledModel& model,
                                         SymmetryKind symmetry);

// The change of events between a and b, located at q (the first orbit with b's events).
OrbitBifurcation classifyEvents(const FamilyPoint& q, const FamilyPoint& a, const FamilyPoint& b);

// How far the orbit through q is from the symmetric orbits of two identical metronomes (in phase:
// theta_1 = theta_2; in antiphase: theta_1 = -theta_2, x = 0): the smaller of the two distances
// of its section state (scaled); infinity when the rig is not an identical pair.
double symmetryDistance(const FamilyPoint& q, const ScaledModel& model);

}  // namespace metrosync::orbit
