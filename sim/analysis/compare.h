// The full model against the slow flow (SPEC section 3): both emit envelope rows on the grid
// tau_k = envelopeTau(eps, k), so rows are matched by their grid index k. Amplitudes are compared
// directly; phase differences modulo 2 pi (the difference wrapped to (-pi, pi]), because after a
// long drift the two unwrapped psi_j may sit on branches a multiple of 2 pi apart. The values
// only: comparison.csv, the reading of envelope CSV files and the summary's JSON are
// tools/report/comparison_csv.h. Rows off the grid -- the start's row at tau = 0 and the final
// row at tau_end (docs/outputs.md) -- are not compared.
#pragma once

#include <functional>
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
  // Adds one pair (same tau). Throws std::invalid_argument for rows of the wrong width.
  void add(const EnvelopeRow& full, const EnvelopeRow& slow);
  ComparisonResult& result() { return result_; }
  const ComparisonResult& result() const { return result_; }

 private:
  ComparisonResult result_;
};

// Index k of a row on the grid tau_k = envelopeTau(epsilon, k).
long envelopeIndex(double epsilon, double tau);

// A stream of rows: fills the row and returns true, or returns false at the end.
using RowSource = std::function<bool(EnvelopeRow&)>;

// Merge-joins two row streams of n metronomes on the grid index: every matched pair goes to the
// comparator and then to `on_pair` (may be empty; a writer's hook); rows without a partner (a run
// that stopped early) are counted.
ComparisonResult joinEnvelopes(
    int n, const RowSource& next_full, const RowSource& next_slow, double epsilon,
    const std::function<void(const EnvelopeRow&, const EnvelopeRow&)>& on_pair = {});

// The number of metronomes of two row vectors (from the first row of either); throws
// std::invalid_argument when both are empty.
int metronomesOf(const std::vector<EnvelopeRow>& full, const std::vector<EnvelopeRow>& slow);
// The rows of a vector, in order (the vector must outlive the source).
RowSource rowSource(const std::vector<EnvelopeRow>& rows);

// The same over two row vectors (n from the first row of either).
ComparisonResult compareEnvelopes(const std::vector<EnvelopeRow>& full,
                                  const std::vector<EnvelopeRow>& slow, double epsilon);

}  // namespace metrosync
