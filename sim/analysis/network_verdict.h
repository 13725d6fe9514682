// What a sweep keeps of a network run (docs/networks.md): the network's label, each platform's
// regime, and the final envelope row, from the run's samples as they stream, without any file.
// The same rules and scales as `metrosync run` on a network (tools/report/network_files.h):
// amplitudes and phases numbered 1..N over the network (metronome 1 the reference), scaled by the
// network's first swinging metronome (Network::scalesRig); a platform's regime is the
// single-platform classifier on its own metronomes; the label is classifyNetwork's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "models/network.h"
#include "sim/analysis/network_regime.h"
#include "sim/analysis/order_parameter.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"

namespace metrosync {

class NetworkVerdict : public StateSink {
 public:
  explicit NetworkVerdict(const Network& net);
  ~NetworkVerdict() override;
  void stateSample(double t, const std::vector<double>& y,
                   const std::vector<PlatformMode>& modes) override;

  bool empty() const;
  // The network's label ("unknown" when no sample fell in the window).
  std::string label() const;
  // Each platform's regime name, in file order ("unknown" for one without swinging metronomes).
  std::vector<std::string> platformRegimes() const;
  // The last sample's envelope row (tau, A_1..A_N, psi_2..psi_N unwrapped; 0 for locked ones) and
  // its overall order parameter r (in last().r).
  const EnvelopeRow& last() const;
  // The last sample's phases of the swinging pendulums (network layout order, per platform
  // block), each platform's order parameter (file order; empty before any sample) and the
  // network's.
  const std::vector<double>& phases() const;
  const std::vector<Order>& groups() const;
  const Order& overall() const;
  // The label's window (its start, rows, each platform's mean r and phase drift).
  const NetworkWindow& window() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace metrosync
