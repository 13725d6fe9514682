#include "tools/report/run_columns.h"

#include <cmath>
#include <sstream>

namespace metrosync {

namespace {

std::vector<std::string> splitHeader(const std::string& header) {
  std::vector<std::string> names;
  std::stringstream ss(header);
  std::string name;
  while (std::getline(ss, name, ',')) names.push_back(name);
  return names;
}

}  // namespace

RunColumns::RunColumns(const RunFilesOptions& opt) : opt_(opt) {
  const int n = opt_.n_metronomes;
  trajectory.names = splitHeader(trajectoryHeader(n));
  envelope.names = splitHeader(envelopeHeader(n) + (opt_.seconds ? ",t_s" : ""));
  for (const std::string& name : splitHeader(eventsHeader(n, opt_.seconds)))
    if (name != "kind" && name != "who") events.names.push_back(name);
}

void RunColumns::trajectoryRow(const std::vector<double>& row) {
  if (!opt_.trajectory) return;
  trajectory.values.insert(trajectory.values.end(), row.begin(), row.end());
}

// The numbers FileSink::envelopeRow prints (formatEnvelopeRow, and t_s)
void RunColumns::envelopeRow(const EnvelopeRow& row) {
  std::vector<double>& v = envelope.values;
  v.push_back(row.tau);
  v.insert(v.end(), row.A.begin(), row.A.end());
  v.insert(v.end(), row.psi.begin(), row.psi.end());
  v.push_back(std::isnan(row.r) ? orderParameter(row.A, row.psi) : row.r);
  if (opt_.seconds) v.push_back(row.tau / opt_.epsilon * opt_.time_unit);
}

// The numbers FileSink::eventRecord prints: t, tau, each state without its t, and t_s
void RunColumns::eventRecord(const char* kind, int metronome, const std::vector<double>& before,
                             const std::vector<double>& after) {
  if (!wantsEventRecords()) return;
  const double t = after[0];
  std::vector<double>& v = events.values;
  v.push_back(t);
  v.push_back(opt_.epsilon * t / opt_.time_unit);
  for (const auto* row : {&before, &after}) v.insert(v.end(), row->begin() + 1, row->end());
  if (opt_.seconds) v.push_back(t);
  event_kinds.emplace_back(kind);
  event_who.push_back(metronome < 0 ? "platform" : std::to_string(metronome + 1));
}

std::vector<EnvelopeRow> RunColumns::envelopeRows() const {
  const size_t n = static_cast<size_t>(opt_.n_metronomes), width = envelope.names.size();
  std::vector<EnvelopeRow> rows(envelope.rows());
  for (size_t k = 0; k < rows.size(); ++k) {
    const double* v = envelope.values.data() + k * width;
    rows[k].tau = v[0];
    rows[k].A.assign(v + 1, v + 1 + n);
    rows[k].psi.assign(v + 1 + n, v + 2 * n);
    rows[k].r = v[2 * n];
  }
  return rows;
}

}  // namespace metrosync
