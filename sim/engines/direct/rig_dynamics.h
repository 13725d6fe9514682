// The single rig's right-hand side as the direct engine's stepper sees it: the rig's minimal
// coordinates (models/network_equations.h: a single board) in the platform's current mode, with the
// number N of swinging pendulums known to the compiler (or kAnyN), and the stepper that integrates
// it. Shared by the rig's model (rig_model.h) and its recorder (rig_recorder.h), which interpolates
// the same steps.
#pragma once

#include "models/network_equations.h"
#include "sim/ode/rk_stepper.h"

namespace metrosync::direct {
// Internal linkage on purpose: see rig_model.h (one includer, direct_engine.cpp).
namespace {

// The right-hand side in the platform's current mode: the stepper inlines it into every stage.
template <int N>
class Dynamics final {
 public:
  explicit Dynamics(const network::NetworkEquations& eq) : eq_(eq) {}
  void eval(const double* y, double* dy) { eq_.rhsN<N>(y, mode, dy); }
  PlatformMode mode = PlatformMode::Stuck;

 private:
  const network::NetworkEquations& eq_;
};

// The state's size for N swinging pendulums: x, xdot, N angles and rates, two ledger quadratures.
constexpr int stateDim(int n) {
  return n > 0 ? 4 + 2 * n : ode::kDynamic;
}

// the ledger's two quadratures (the damping's and friction's work) are not in the stages
template <int N>
using RigStepper = ode::RkStepperT<Dynamics<N>, stateDim(N), 2>;

}  // namespace
}  // namespace metrosync::direct
