// A run's rows kept in memory, as the columns of the files FileSink writes (tools/report/
// outputs.h): trajectory.csv, envelope.csv and events.csv, with the same column names and the
// numbers those files print, before printing (the engine's doubles; the files round them to 12
// significant digits, tau to 10). The Python module's results (tools/python, docs/python.md):
// a FileSink hands its rows to a RunColumns as its tap, with or without files.
#pragma once

#include <string>
#include <vector>

#include "sim/record/run_report.h"
#include "tools/report/outputs.h"

namespace metrosync {

// Rows of numbers, row-major: rows() x names.size() values.
struct ColumnTable {
  std::vector<std::string> names;
  std::vector<double> values;
  size_t rows() const { return names.empty() ? 0 : values.size() / names.size(); }
};

class RunColumns : public RunSink {
 public:
  // opt: the options the run's FileSink has (its widths, units and which files it writes)
  explicit RunColumns(const RunFilesOptions& opt);

  void trajectoryRow(const std::vector<double>& row) override;
  void envelopeRow(const EnvelopeRow& row) override;
  bool wantsEventRecords() const override { return opt_.trajectory && opt_.events; }
  void eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                   const std::vector<double>& after) override;

  // trajectory.csv's columns (no row for the slow flow)
  ColumnTable trajectory;
  // envelope.csv's: tau, A_1..A_N, psi_2..psi_N, r, and t_s for a physical rig
  ColumnTable envelope;
  // events.csv's numeric columns (its header without kind and who), and those two as text:
  // kind "tick" | "stick" | "slip", who "1".."N" | "platform"
  ColumnTable events;
  std::vector<std::string> event_kinds, event_who;

  // The envelope's rows again as EnvelopeRow values (compare's comparison in memory).
  std::vector<EnvelopeRow> envelopeRows() const;

 private:
  RunFilesOptions opt_;
};

}  // namespace metrosync
