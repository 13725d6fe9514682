// The direct engine's entries: a single rig and a network of platforms, each the one run
// (sim/engines/direct/direct_run.h) over its model (rig_model.h: N known to the compiler up to
// NetworkEquations::kMaxFixedN; network_model.h). What the run does, top to bottom:
//   1. witnesses (sim/events/witness.h), each turned into one that rises through zero at its
//      event: ticks side * theta_i - theta_c,i (only while armed, sim/events/resolver.h); each
//      contact's PlatformWitness with the sign flipped (|H| - bound while stuck, -mode * slip
//      velocity while slipping), in one list (sim/events/witness_list.h).
//   2. detection on each kept step (the list's): a sign change between the step's ends, or a
//      hidden double crossing (grazing) found at the extreme of the witness inside the step (the
//      root of its rate on the dense output); then each crossing is bracketed on the dense output
//      to a few ulps. The window ends at the earliest bracket's upper end; every witness past zero
//      there belongs to it (its sign decides, not its bracket: near a root the dense output is not
//      monotone at the ulp level).
//   3. the shared resolver of each platform (sim/events/resolver.h) acts on the window's end
//      state through the model's view of that platform; supports moved by another's impulse settle.
//   4. the model's recorders: trajectory rows and envelope samples (a rig) or states (a network)
//      from the dense output; the energy ledger from the state's quadratures.
#include "sim/engines/direct/direct_engine.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "models/network_equations.h"
#include "sim/engines/direct/direct_run.h"
#include "sim/engines/direct/network_model.h"
#include "sim/engines/direct/rig_model.h"

namespace metrosync {

namespace direct {
namespace {

template <int N>
RunReport runRig(const Rig& rig, RunSink& sink, const DirectOptions& options) {
  return DirectRun<RigModel<N>>(options, rig, sink).run();
}

}  // namespace
}  // namespace direct

RunReport runDirectModel(const Rig& rig, RunSink& sink, const DirectOptions& options) {
  const auto& names = directIntegratorNames();
  if (!rig.sim.integrator.empty() &&
      std::find(names.begin(), names.end(), rig.sim.integrator) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("simulation.integrator = " + rig.sim.integrator +
                                ": not an integrator of the direct engine (one of: " + list + ")");
  }
  // the state's size known to the compiler for up to kMaxFixedN swinging pendulums (every loop
  // over the state unrolled, every buffer in the run object), dynamic above: the same bits
  const int n = network::NetworkEquations(rig).numSwinging();
  switch (n) {
    case 1:
      return direct::runRig<1>(rig, sink, options);
    case 2:
      return direct::runRig<2>(rig, sink, options);
    case 3:
      return direct::runRig<3>(rig, sink, options);
    case 4:
      return direct::runRig<4>(rig, sink, options);
    case 5:
      return direct::runRig<5>(rig, sink, options);
    case 6:
      return direct::runRig<6>(rig, sink, options);
    case 7:
      return direct::runRig<7>(rig, sink, options);
    case 8:
      return direct::runRig<8>(rig, sink, options);
    default:
      return direct::runRig<network::NetworkEquations::kAnyN>(rig, sink, options);
  }
}

RunReport runNetworkDirect(const Network& net, RunSink& sink) {
  return direct::DirectRun<direct::NetworkModel>(DirectOptions{}, net, sink).run();
}

}  // namespace metrosync
