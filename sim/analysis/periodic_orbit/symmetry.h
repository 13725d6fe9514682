// The symmetric orbits of two identical metronomes, and the subspace of section coordinates they
// live in. The equations are invariant under exchanging the metronomes (in phase: theta_1 =
// theta_2, platform free) and under exchanging them mirrored (in antiphase: theta_1 = -theta_2,
// x = xdot = 0: the platform never moves, their ticks cancel exactly). A symmetric orbit's family
// is followed inside the symmetric subspace (u = B w, B orthonormal): there the return map is
// exactly symmetric, while across it the engine merges ticks that fall within its escapement
// slack (contact/escapement.h: 1e-9 of theta_c) into one window, so that the map is not the
// linearized one within ~1e-9 of the subspace. The antisymmetric complement C carries the
// symmetry-breaking multipliers: det(C^T (dP/du - I) C) changes sign at a branch point.
#pragma once

#include <string>

#include "sim/analysis/periodic_orbit/return_map.h"

namespace metrosync::orbit {

enum class SymmetryKind { None, InPhase, AntiPhase };
const char* toString(SymmetryKind k);

struct SymmetryReduction {
  SymmetryKind kind = SymmetryKind::None;
  Mat B;  // (m x k) symmetric subspace, orthonormal columns (the identity for None)
  Mat C;  // (m x (m - k)) its orthonormal complement (empty for None)
};

// Whether the rig's swinging pendulums are two identical metronomes (same scaled parameters).
bool identicalPair(const ScaledModel& model);

// How far the state z is from the in-phase and from the antiphase symmetric states (scaled):
// max |theta_1 - theta_2|, |thetadot_1 - thetadot_2| and max |theta_1 + theta_2|, |thetadot_1 +
// thetadot_2|, |x|, |xdot|; infinity when the rig is not an identical pair.
double inPhaseDistance(const ScaledModel& model, const Vec& z);
double antiPhaseDistance(const ScaledModel& model, const Vec& z);

// The reduction of `kind` for the map's section coordinates.
SymmetryReduction reduction(const ReturnMap& map, SymmetryKind kind);

}  // namespace metrosync::orbit
