// Neutral families: where the solutions of F(x, p) = 0 through x form a continuum at one value of
// p -- k directions along which F_x stays singular at every member (in the slow flow: the
// metronomes uncoupled by a stuck platform, each one's phase free, every phase difference with
// s <= 1 a locked state). Newton cannot converge onto one member and a branch has no tangent
// there, so a family is followed as a whole:
//   detection   k singular values of F_x below kNeutral (relative), confirmed by a second member
//               found at a distance along the first null direction v;
//   a member    the unfolded system F(x, p) + W l = 0, V^T (x - x_r) = c (W, V the left and
//               right null vectors, l in R^k; l = 0 at every member: Muñoz-Almaraz et al.'s
//               unfolding), regular, solved by Newton;
//   the extent  the members at fixed p traced along v (the same pseudo-arclength core, in c) both
//               ways until a border of the region (e.g. s = 1: the platform starts to slip) or
//               back at the start (a closed family);
//   in p        natural-parameter steps, each from the previous representative, re-centred at
//               the middle of the extent so that it stays inside; the family ends where no member
//               persists (W^T F_p != 0: it exists at one value of p only), at a border, or at the
//               range's end.
// Stability: the eigenvalues but the k of the neutral directions (a family whose other
// eigenvalues are negative attracts; along it the motion is neutral).
#pragma once

#include <optional>

#include "sim/analysis/continuation/branch.h"

namespace metrosync::continuation {

struct NeutralDirections {
  Mat V, W;  // right and left null vectors of F_x, n x k
};

// The neutral directions of F_x at the solution (x, p) when a family passes through it.
std::optional<NeutralDirections> neutralDirections(const ContinuationSystem& sys, const Vec& x,
                                                   double p, const Region& region);

// A member of the family through x (a solution of region's formulas, maybe just outside the
// region: a slow-flow run stops where the platform sticks, on the border s = 1) inside the region,
// by steps along the first neutral direction; nullopt when there is none within kReach.
std::optional<Vec> memberInside(const ContinuationSystem& sys, const NeutralDirections& nd,
                                const Vec& x, double p, const Region& region);

// The family through the solution (x0, p0) over [s.p_min, s.p_max]: a Branch whose points are
// its representative members (tangent along p), with `neutral` and `extent` set.
Branch followFamily(const ContinuationSystem& sys, const Vec& x0, double p0, const Region& region,
                    const NeutralDirections& nd, const ContinuationSettings& s);

}  // namespace metrosync::continuation
