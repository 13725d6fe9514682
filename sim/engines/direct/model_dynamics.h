// The right-hand side as the direct engine's stepper sees it, and the stepper that integrates it:
// the rig's minimal coordinates (models/network_equations.h) in its contacts' current modes. A
// model's kind K says what the compiler knows: a single board (one platform on the table, no
// damper, no coupling) with K = N swinging pendulums (1 .. kMaxFixedN) or kAnyN, through its
// fused entry; or a network of platforms (kNetwork), through the general equations. Shared by the
// direct model (direct_model.h) and the single board's recorder (rig_recorder.h), which
// interpolates the same steps.
#pragma once

#include <vector>

#include "models/network_equations.h"
#include "sim/ode/rk_stepper.h"

namespace metrosync::direct {

// The model's kind for a network of platforms: no single board's fused entry.
constexpr int kNetwork = -2;
constexpr bool singleBoard(int kind) {
  return kind != kNetwork;
}

// Internal linkage on purpose: see direct_model.h (one includer, direct_engine.cpp).
namespace {

// The right-hand side in the contacts' current modes: the stepper inlines it into every stage.
// A single board's one mode is a plain member (read once per stage: one load, not two).
template <int K>
class Dynamics final {
 public:
  Dynamics(const network::NetworkEquations& eq, int platforms)
      : modes(singleBoard(K) ? 0 : platforms, PlatformMode::Stuck), eq_(eq) {}
  void eval(const double* y, double* dy) {
    if constexpr (singleBoard(K))
      eq_.rhsN<K>(y, mode, dy);
    else
      eq_.rhs(y, modes, dy);
  }
  // the contacts' modes: a single board's, or a network's (one per platform)
  PlatformMode mode = PlatformMode::Stuck;
  std::vector<PlatformMode> modes;
  PlatformMode of(int p) const {
    if constexpr (singleBoard(K))
      return mode;
    else
      return modes[p];
  }
  void set(int p, PlatformMode m) {
    if constexpr (singleBoard(K))
      mode = m;
    else
      modes[p] = m;
  }
  // what the recording takes: the single board's mode, or the network's modes
  const auto& recorded() const {
    if constexpr (singleBoard(K))
      return mode;
    else
      return modes;
  }

 private:
  const network::NetworkEquations& eq_;
};

// The state's size known to the compiler: a single board of N swinging pendulums has x, xdot,
// N angles and rates and two ledger quadratures.
constexpr int stateDim(int kind) {
  return kind > 0 ? 4 + 2 * kind : ode::kDynamic;
}
// A single board's two ledger quadratures (the damping's and friction's work) are not in the
// stages; a network's ledger is integrated with its state.
constexpr int quadratures(int kind) {
  return singleBoard(kind) ? 2 : 0;
}

template <int K>
using ModelStepper = ode::RkStepperT<Dynamics<K>, stateDim(K), quadratures(K)>;

}  // namespace
}  // namespace metrosync::direct
