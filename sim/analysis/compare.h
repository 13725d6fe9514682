// The full model against the slow flow (SPEC section 3, comparison.csv): both emit envelope rows
// on the grid tau_k = envelopeTau(eps, k), so rows are matched by their grid index k. Amplitudes
// are compared directly; phase differences modulo 2 pi (the difference wrapped to (-pi, pi]),
// because after a long drift the two unwrapped psi_j may sit on branches a multiple of 2 pi
// apart. comparison.csv keeps each model's psi_j as it wrote it. Rows off the grid -- the start's
// row at tau = 0 and the final row at tau_end (docs/outputs.md) -- are not compared.
#pragma once

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/record/envelope.h"

namespace metrosync {

struct ComparisonResult {
  int n = 0;                         // metronomes
  std::vector<double> max_abs_dA;    // (N x 1) max over tau of |A_i,full - A_i,slow|
  std::vector<double> max_abs_dpsi;  // (N-1 x 1) max over tau of |wrap(psi_j,full - psi_j,slow)|
  std::vector<double> tau_max_dA;    // (N x 1) where the maximum occurs
  std::vector<double> tau_max_dpsi;  // (N-1 x 1)
  long rows = 0;                     // matched rows (lines of comparison.csv)
  long unmatched_full = 0;           // rows of one model with no partner in the other
  long unmatched_slow = 0;
};

// Accumulates matched row pairs; streaming, O(N) memory.
class EnvelopeComparator {
 public:
  explicit EnvelopeComparator(int n);
  // tau,A_1_full,A_1_slow,...,A_N_full,A_N_slow,psi_2_full,psi_2_slow,...,psi_N_full,psi_N_slow
  std::string header() const;
  // Adds one pair (same tau) and returns its comparison.csv line (no newline).
  std::string add(const EnvelopeRow& full, const EnvelopeRow& slow);
  ComparisonResult& result() { return result_; }
  const ComparisonResult& result() const { return result_; }

 private:
  ComparisonResult result_;
};

// Index k of a row on the grid tau_k = envelopeTau(epsilon, k).
long envelopeIndex(double epsilon, double tau);

// Reads an envelope.csv one row at a time (readEnvelopeCsv holds the whole file).
class EnvelopeCsvReader {
 public:
  explicit EnvelopeCsvReader(const std::string& path);  // throws std::runtime_error
  int n() const { return n_; }
  // false at the end of the file; throws std::runtime_error on a malformed line
  bool next(EnvelopeRow& row);

 private:
  std::string path_;
  std::ifstream in_;
  EnvelopeLayout layout_;
  int n_ = 0;
  long lineno_ = 1;
};

// Joins the two row streams on the grid index and writes comparison.csv to `out_csv` atomically.
// Rows without a partner (a run that stopped early) are counted, not written.
ComparisonResult compareEnvelopes(const std::vector<EnvelopeRow>& full,
                                  const std::vector<EnvelopeRow>& slow, double epsilon,
                                  const std::string& out_csv);
// The same from two envelope CSV files, streaming.
ComparisonResult compareEnvelopeFiles(const std::string& full_csv, const std::string& slow_csv,
                                      double epsilon, const std::string& out_csv);

// {max_abs_dA[], max_abs_dpsi[], tau_max_dA[], tau_max_dpsi[], rows, unmatched_full,
// unmatched_slow}; a maximum over no row is null.
nlohmann::json comparisonJson(const ComparisonResult& r);

}  // namespace metrosync
