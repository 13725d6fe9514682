// The direct engine's entry: the one run (sim/engines/direct/direct_run.h) over the one model
// (direct_model.h) of the rig's kind: a single board with N known to the compiler up to
// NetworkEquations::kMaxFixedN, or a network. What the run does, top to bottom:
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
//   4. the model's recording: trajectory rows and envelope samples (a rig) or states (a network)
//      from the dense output; the energy ledger from the state's quadratures.
#include "sim/engines/direct/direct_engine.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "models/network_equations.h"
#include "sim/engines/direct/direct_model.h"
#include "sim/engines/direct/direct_run.h"

namespace metrosync {

namespace direct {
namespace {

template <int K>
RunReport runKind(const Network& net, const Rig& rig, RunSink& sink, const DirectOptions& options) {
  return DirectRun<DirectModel<K>>(options, net, rig, sink).run();
}

// A single board with its number N of swinging pendulums known to the compiler up to
// kMaxFixedN (every loop over the state unrolled, every buffer in the run object), dynamic
// above: the same bits.
RunReport runSingleBoard(const Network& net, const Rig& rig, RunSink& sink,
                         const DirectOptions& options) {
  const network::NetworkEquations eq(net);
  // air drag only where N is not known (its rates out of the hot path: models/platform_arrow.h)
  if (eq.arrow().hasDrag())
    return runKind<network::NetworkEquations::kAnyN>(net, rig, sink, options);
  switch (eq.numSwinging()) {
    case 1:
      return runKind<1>(net, rig, sink, options);
    case 2:
      return runKind<2>(net, rig, sink, options);
    case 3:
      return runKind<3>(net, rig, sink, options);
    case 4:
      return runKind<4>(net, rig, sink, options);
    case 5:
      return runKind<5>(net, rig, sink, options);
    case 6:
      return runKind<6>(net, rig, sink, options);
    case 7:
      return runKind<7>(net, rig, sink, options);
    case 8:
      return runKind<8>(net, rig, sink, options);
    default:
      return runKind<network::NetworkEquations::kAnyN>(net, rig, sink, options);
  }
}

}  // namespace
}  // namespace direct

RunReport runDirect(const Network& net, RunSink& sink, const DirectOptions& options) {
  const auto& names = directIntegratorNames();
  const std::string& integrator = net.sim.integrator;
  if (!integrator.empty() && std::find(names.begin(), names.end(), integrator) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("simulation.integrator = " + integrator +
                                ": not an integrator of the direct engine (one of: " + list + ")");
  }
  // the model's kind from the rig's shape, never from the sink
  const Rig rig = net.isSingleRig() ? net.toSingleRig() : Rig{};
  if (net.isSingleRig() && !options.general_equations)
    return direct::runSingleBoard(net, rig, sink, options);
  return direct::runKind<direct::kNetwork>(net, rig, sink, options);
}

RunReport runDirectModel(const Rig& rig, RunSink& sink, const DirectOptions& options) {
  return runDirect(networkOfOne(rig), sink, options);
}

}  // namespace metrosync
