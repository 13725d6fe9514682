// Pseudo-arclength continuation of a family of periodic orbits of the full model in one rig key
// (Keller; the slow flow's own is sim/analysis/continuation/arclength.h): from a converged orbit,
// both ways, predictor along the tangent in y = (u, p / span), the corrector of family_map.h,
// steps grown after an easy corrector (<= 3 iterations) and halved after a failure. Between two
// points the test functions of special_points.h and the events of a period are compared; a
// change is located on the step (Illinois regula falsi on the arclength for a test function,
// bisection for the events, both to 1e-9 of the parameter's range) and classified. A family stops
// at the end of the range, after max_points, where the corrector fails at a tiny step (an orbit
// that ends: a grazing tick, an engine failure), or at a symmetry-breaking branch point reached
// along the asymmetric orbits (beyond it lies their mirror image).
#pragma once

#include <optional>

#include "sim/analysis/periodic_orbit/family.h"

namespace metrosync::orbit {

// The family through `start` (a converged orbit at p0, on problem.rig_at(p0)'s section).
Family continueFamily(const OrbitProblem& problem, const Orbit& start, double p0,
                      const FamilySettings& settings);

// The asymmetric family that branches off a symmetric family of `symmetry` at its branch point
// `at` (a located "branch"): the first orbit a step along the antisymmetric kernel direction of
// dP/du - I (the corrector's hyperplane keeps it off the symmetric orbit), then both ways; the
// way back through the branch point ends there (beyond it lies the mirror image). nullopt when
// the corrector falls back onto the symmetric orbits or fails.
std::optional<Family> switchBranch(const OrbitProblem& problem, SymmetryKind symmetry,
                                   const FamilyPoint& at, const FamilySettings& settings);

}  // namespace metrosync::orbit
