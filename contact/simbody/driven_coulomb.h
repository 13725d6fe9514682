// The full model's Coulomb contact (contact/simbody/coulomb_contact.h) on its own, in the set-up
// of the paper's appendix "ac" (eq. c1): a unit mass on a Simbody slider with unit Coulomb
// friction, driven by the prescribed force B sin t, switched by the law's rules (the contact's
// witness; resolveSwitch, settleAtRest in driven_coulomb_harness.h). Started from rest, it is
// run until its switch instants repeat from one period to the next (the periodic steady state);
// the acceleration y'' over that period then gives the slow flow's averaged coefficients by
// Fourier projection,
//   beta1 = (1 / (2 pi B)) int y'' sin t dt,   beta2 = (1 / (2 pi B)) int y'' cos t dt,
// to be held against the closed forms (eq. d2, contact/averaged_response.h).
//
// y'' is smooth between switch instants (B sin t - mode while slipping, 0 while stuck), so the
// integral is taken piece by piece with Gauss-Legendre nodes: exact to rounding, so that what is
// measured is the element (where it switches and what force it applies), not a quadrature.
//
// This header has no Simbody type in it (core code may name the result type).
#pragma once

#include <vector>

#include "contact/simbody/driven_coulomb_switch.h"

namespace metrosync {

struct DrivenCoulombOptions {
  // integrator's relative local error target: the switch instants come out to ~1e-12 and the
  // betas to ~1e-11 (measured), four orders below the 1e-7 the validation asks for
  double accuracy = 1e-10;
  int max_periods = 400;  // give up (periodic = false) after this many drive periods
  // steady: switch instants repeat (mod 2 pi) to within this; the betas then differ from their
  // periodic values by about as much (the slip regime forgets its start geometrically)
  double periodic_tol = 1e-9;
  int gauss_nodes = 16;  // per smooth piece; 16 nodes integrate B sin t sin t exactly to rounding
};

struct DrivenCoulombMeasurement {
  double B = 0.0;
  double beta1 = 0.0, beta2 = 0.0;  // measured, eq. d2's definition
  bool periodic = false;            // steady state reached within max_periods
  int periods = 0;                  // drive periods run before the measured one
  double period_mismatch = 0.0;     // max shift of a switch instant between the last two periods
  std::vector<DrivenCoulombSwitch> switches;  // in the measured period [t_start, t_start + 2 pi)
  double t_start = 0.0;                       // start of the measured period
  double wall_seconds = 0.0;
};

// Runs the harness at drive strength B > 0 (= s, the bound being 1); throws
// std::invalid_argument otherwise. A run that does not settle says periodic = false (betas NaN).
DrivenCoulombMeasurement measureDrivenCoulomb(double B, const DrivenCoulombOptions& opt = {});

}  // namespace metrosync
