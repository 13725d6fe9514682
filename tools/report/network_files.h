// The output files of a network run (docs/networks.md), streamed sample by sample:
//   trajectory.csv  t, then per platform x_NAME,xdot_NAME,platform_NAME (file order), then
//                   theta_i,thetadot_i numbered 1..N over the whole network (file order)
//   envelope.csv    tau,A_1..A_N,psi_2..psi_N,r in that numbering (scaled, as a single rig's)
//   order.csv       tau,r_NAME,Phi_NAME,...,r,Phi (Kuramoto, sim/analysis/order_parameter.h)
// and what summary.json adds: per platform its regime (the single-platform classifier on its own
// metronomes), its metronomes' global numbers and final r; the network's label and final r.
// Scales (tau, scaled A) are those of the network's first swinging metronome.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/network.h"
#include "sim/record/run_report.h"
#include "tools/report/output_dir.h"

namespace metrosync {

// A network's part of the one file writer (FileSink, tools/report/outputs.h, which hands it the
// run's states).
class NetworkFiles {
 public:
  NetworkFiles(const OutputDir& dir, const Network& net);
  ~NetworkFiles();
  // one sample (RunSink::stateSample)
  void add(double t, const std::vector<double>& y, const std::vector<PlatformMode>& modes);
  void commit();
  std::vector<std::string> fileNames() const;
  // the network's verdict in summary.json (runSummaryJson, tools/report/outputs.h): a single
  // rig's keys (`final`, `regime`, `regime_window`) and `platforms` (each with its regime,
  // metronomes, final r and final envelope), `network` (label, final r)
  nlohmann::json verdictJson(const RunReport& report) const;
  // the time series for the plots: tau, then r per platform and overall, one row per sample
  const std::vector<std::vector<double>>& orderRows() const { return order_rows_; }
  // per sample: tau and each swinging metronome's phase relative to its platform's mean phase
  const std::vector<std::vector<double>>& rasterRows() const { return raster_rows_; }

 private:
  nlohmann::json platformsJson(bool complete) const;
  nlohmann::json regimeWindowJson() const;
  void keepForPlots(const std::vector<double>& order, const std::vector<double>& raster);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::vector<double>> order_rows_, raster_rows_;
};

}  // namespace metrosync
