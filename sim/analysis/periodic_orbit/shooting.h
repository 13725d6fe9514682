// A locked state of the full model as a fixed point of the return map: Newton on P(u) - u = 0,
// the Jacobian dP/du - I from the variational equations and the saltation matrices
// (return_map.h). The section fixes the phase, so no phase condition is needed; the period is
// the return time at the fixed point. The multipliers of dP/du there are the orbit's nontrivial
// Floquet multipliers.
#pragma once

#include <optional>
#include <string>

#include "sim/analysis/periodic_orbit/return_map.h"

namespace metrosync::orbit {

using CVec = Eigen::VectorXcd;

struct NewtonSettings {
  // max |P(u) - u| (scaled) accepted: the 1e-10, with the return map's noise (~1e-12)
  // two orders below it
  double tolerance = 1e-10;
  int max_iterations = 16;
};

// A periodic orbit: its section state, period, return map Jacobian and multipliers.
struct Orbit {
  Vec u;  // the fixed point on the section
  double period = 0.0;
  double residual = 0.0;  // max |P(u) - u| at u
  int iterations = 0;
  Pass pass;         // the pass from u (with its Jacobian)
  CVec multipliers;  // eigenvalues of dP/du, by decreasing modulus
  // the platform's velocity is neutral (neutralVelocity): its multiplier 1 is left out of
  // maxModulus, which then says whether the orbit attracts at its own drift
  bool neutral = false;
  double maxModulus() const;
};

// The multipliers of a return map Jacobian, by decreasing modulus.
CVec multipliersOf(const Mat& jacobian);

// Whether the platform's velocity on the section is neutral at this Jacobian: a perturbation of
// it comes back unchanged and moves nothing else (its column of dP/du is the unit vector). So it
// is where the platform slips throughout and its slip reverses only at ticks (Coulomb friction
// then does not see the velocity's size), or on a platform without friction (Galilean
// invariance): the orbits form a family in the platform's drift and are not isolated.
bool neutralVelocity(const Section& section, const Mat& jacobian);

// Newton from u0; nullopt (with `why`) when it does not converge or the orbit is lost. With a
// `basis` B (m x k, orthonormal columns: a subspace the return map keeps, symmetry.h) Newton runs
// in u = B w on B^T (P(u) - u) from B B^T u0; `residual` is still the whole max |P(u) - u|.
std::optional<Orbit> shoot(const ReturnMap& map, const Vec& u0, double period_guess,
                           const NewtonSettings& settings = {}, std::string* why = nullptr,
                           const Mat* basis = nullptr);

}  // namespace metrosync::orbit
