// comparison.csv (SPEC section 3) and the comparison's summary JSON, from the values of
// sim/analysis/compare.h: the file parts of `compare`. comparison.csv keeps each model's psi_j
// as it wrote it.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/compare.h"
#include "sim/record/envelope.h"
#include "sim/record/envelope_csv.h"
#include "tools/report/run_columns.h"

namespace metrosync {

// tau,A_1_full,A_1_slow,...,A_N_full,A_N_slow,psi_2_full,psi_2_slow,...,psi_N_full,psi_N_slow
std::string comparisonCsvHeader(int n);
// One matched pair's line (no newline).
std::string comparisonCsvLine(const EnvelopeRow& full, const EnvelopeRow& slow);

// compareEnvelopes, and comparison.csv written to `out_csv` atomically. Rows without a partner
// (a run that stopped early) are counted, not written. seconds_per_tau > 0 (a physical rig): a
// last column t_s, the row's tau in seconds.
ComparisonResult writeComparisonCsv(const std::vector<EnvelopeRow>& full,
                                    const std::vector<EnvelopeRow>& slow, double epsilon,
                                    const std::string& out_csv, double seconds_per_tau = 0.0);
// The same from two envelope CSV files, streaming.
ComparisonResult compareEnvelopeFiles(const std::string& full_csv, const std::string& slow_csv,
                                      double epsilon, const std::string& out_csv,
                                      double seconds_per_tau = 0.0);

// comparison.csv's columns in memory (the Python module's compare): its header's names (t_s when
// seconds_per_tau > 0) and the numbers its lines print, from two row vectors of n metronomes;
// returns the comparison of those rows.
ComparisonResult comparisonColumns(int n, const std::vector<EnvelopeRow>& full,
                                   const std::vector<EnvelopeRow>& slow, double epsilon,
                                   double seconds_per_tau, ColumnTable& table);

// {max_abs_dA[], max_abs_dpsi[], tau_max_dA[], tau_max_dpsi[], rows, unmatched_full,
// unmatched_slow}; a maximum over no row is null.
nlohmann::json comparisonJson(const ComparisonResult& r);

}  // namespace metrosync
