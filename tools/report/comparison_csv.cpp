#include "tools/report/comparison_csv.h"

#include <cstdio>
#include <stdexcept>

#include "base/csv.h"
#include "base/number_text.h"
#include "sim/record/atomic_file.h"

namespace metrosync {

namespace {

void appendNumber(std::string& s, double v) {
  s += "," + numberText(v, 12);
}

// joinEnvelopes with every matched pair written to out_csv, committed at the end.
// seconds_per_tau > 0 (a physical rig): a last column t_s = tau * seconds_per_tau.
ComparisonResult joinAndWrite(int n, const RowSource& next_full, const RowSource& next_slow,
                              double epsilon, const std::string& out_csv, double seconds_per_tau) {
  AtomicFile out(out_csv);
  const bool t_s = seconds_per_tau > 0;
  out.writeLine(comparisonCsvHeader(n) + (t_s ? ",t_s" : ""));
  const ComparisonResult r = joinEnvelopes(n, next_full, next_slow, epsilon,
                                           [&](const EnvelopeRow& f, const EnvelopeRow& s) {
                                             std::string line = comparisonCsvLine(f, s);
                                             if (t_s) appendNumber(line, f.tau * seconds_per_tau);
                                             out.writeLine(line);
                                           });
  out.commit();
  return r;
}

}  // namespace

std::string comparisonCsvHeader(int n) {
  std::string h = "tau";
  for (int i = 1; i <= n; ++i) {
    const std::string a = ",A_" + std::to_string(i);
    h += a + "_full" + a + "_slow";
  }
  for (int j = 2; j <= n; ++j) {
    const std::string p = ",psi_" + std::to_string(j);
    h += p + "_full" + p + "_slow";
  }
  return h;
}

std::string comparisonCsvLine(const EnvelopeRow& full, const EnvelopeRow& slow) {
  std::string line = numberText(full.tau, 10);
  for (size_t i = 0; i < full.A.size(); ++i) {
    appendNumber(line, full.A[i]);
    appendNumber(line, slow.A[i]);
  }
  for (size_t j = 0; j < full.psi.size(); ++j) {
    appendNumber(line, full.psi[j]);
    appendNumber(line, slow.psi[j]);
  }
  return line;
}

ComparisonResult writeComparisonCsv(const std::vector<EnvelopeRow>& full,
                                    const std::vector<EnvelopeRow>& slow, double epsilon,
                                    const std::string& out_csv, double seconds_per_tau) {
  return joinAndWrite(metronomesOf(full, slow), rowSource(full), rowSource(slow), epsilon, out_csv,
                      seconds_per_tau);
}

ComparisonResult compareEnvelopeFiles(const std::string& full_csv, const std::string& slow_csv,
                                      double epsilon, const std::string& out_csv,
                                      double seconds_per_tau) {
  EnvelopeCsvReader full(full_csv), slow(slow_csv);
  if (full.n() != slow.n())
    throw std::runtime_error(full_csv + " has " + std::to_string(full.n()) + " metronomes, " +
                             slow_csv + " has " + std::to_string(slow.n()));
  return joinAndWrite(
      full.n(), [&](EnvelopeRow& r) { return full.next(r); },
      [&](EnvelopeRow& r) { return slow.next(r); }, epsilon, out_csv, seconds_per_tau);
}

ComparisonResult comparisonColumns(int n, const std::vector<EnvelopeRow>& full,
                                   const std::vector<EnvelopeRow>& slow, double epsilon,
                                   double seconds_per_tau, ColumnTable& table) {
  const bool t_s = seconds_per_tau > 0;
  table = ColumnTable{};
  table.names = csvCells(comparisonCsvHeader(n) + (t_s ? ",t_s" : ""));
  std::vector<double>& v = table.values;
  // the numbers of comparisonCsvLine, in its order
  return joinEnvelopes(n, rowSource(full), rowSource(slow), epsilon,
                       [&](const EnvelopeRow& f, const EnvelopeRow& s) {
                         v.push_back(f.tau);
                         for (size_t i = 0; i < f.A.size(); ++i)
                           v.insert(v.end(), {f.A[i], s.A[i]});
                         for (size_t j = 0; j < f.psi.size(); ++j)
                           v.insert(v.end(), {f.psi[j], s.psi[j]});
                         if (t_s) v.push_back(f.tau * seconds_per_tau);
                       });
}

nlohmann::json comparisonJson(const ComparisonResult& r) {
  auto orNull = [&](const std::vector<double>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (double x : v) a.push_back(r.rows > 0 ? nlohmann::json(x) : nlohmann::json(nullptr));
    return a;
  };
  return {{"max_abs_dA", orNull(r.max_abs_dA)},
          {"max_abs_dpsi", orNull(r.max_abs_dpsi)},
          {"tau_max_dA", orNull(r.tau_max_dA)},
          {"tau_max_dpsi", orNull(r.tau_max_dpsi)},
          {"rows", r.rows},
          {"unmatched_full", r.unmatched_full},
          {"unmatched_slow", r.unmatched_slow}};
}

}  // namespace metrosync
