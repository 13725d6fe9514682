#include "sim/analysis/compare.h"

#include <cmath>
#include <stdexcept>

#include "base/constants.h"
#include "sim/analysis/regime.h"

namespace metrosync {

namespace {

// Keeps the largest |d| and where it occurred; a NaN, once seen, sticks (it means a broken row).
void updateMax(double d, double tau, double& max, double& tau_at) {
  if (std::isnan(max)) return;
  if (std::isnan(d) || d > max) {
    max = d;
    tau_at = tau;
  }
}

}  // namespace

EnvelopeComparator::EnvelopeComparator(int n) {
  if (n < 1) throw std::invalid_argument("EnvelopeComparator: no metronome");
  result_.n = n;
  result_.max_abs_dA.assign(n, 0.0);
  result_.tau_max_dA.assign(n, 0.0);
  result_.max_abs_dpsi.assign(n - 1, 0.0);
  result_.tau_max_dpsi.assign(n - 1, 0.0);
}

void EnvelopeComparator::add(const EnvelopeRow& full, const EnvelopeRow& slow) {
  const size_t n = static_cast<size_t>(result_.n);
  if (full.A.size() != n || slow.A.size() != n || full.psi.size() != n - 1 ||
      slow.psi.size() != n - 1)
    throw std::invalid_argument("EnvelopeComparator: rows of the wrong width");
  for (size_t i = 0; i < n; ++i)
    updateMax(std::fabs(full.A[i] - slow.A[i]), full.tau, result_.max_abs_dA[i],
              result_.tau_max_dA[i]);
  // modulo 2 pi: the two unwrapped phases may be on branches a multiple of 2 pi apart
  for (size_t j = 0; j + 1 < n; ++j)
    updateMax(std::fabs(wrapToPi(full.psi[j] - slow.psi[j])), full.tau, result_.max_abs_dpsi[j],
              result_.tau_max_dpsi[j]);
  ++result_.rows;
}

long envelopeIndex(double epsilon, double tau) {
  return std::lround(tau / (epsilon * kTwoPi) - 0.5);
}

// Only the grid rows are compared: the start's row (tau = 0) and the final row (tau_end: the
// full model's last period, the slow flow's state at the end) are not on the grid. A grid row's
// tau is envelopeTau(k) to the 10 significant digits envelope.csv keeps (kCsvTauRelative |tau|),
// plus kGridSlackPeriods of a period for rounding: both far below the rows' spacing of a period.
constexpr double kCsvTauRelative = 2e-9;
constexpr double kGridSlackPeriods = 1e-6;

RowSource gridRowsOf(RowSource next, double epsilon) {
  return [next, epsilon](EnvelopeRow& row) {
    while (next(row)) {
      const double off = row.tau - envelopeTau(epsilon, envelopeIndex(epsilon, row.tau));
      const double slack =
          kGridSlackPeriods * epsilon * kTwoPi + kCsvTauRelative * std::fabs(row.tau);
      if (std::fabs(off) <= slack) return true;
    }
    return false;
  };
}

ComparisonResult joinEnvelopes(
    int n, const RowSource& next_full_all, const RowSource& next_slow_all, double epsilon,
    const std::function<void(const EnvelopeRow&, const EnvelopeRow&)>& on_pair) {
  const RowSource next_full = gridRowsOf(next_full_all, epsilon);
  const RowSource next_slow = gridRowsOf(next_slow_all, epsilon);
  EnvelopeComparator cmp(n);
  EnvelopeRow f, s;
  bool have_f = next_full(f), have_s = next_slow(s);
  long unmatched_full = 0, unmatched_slow = 0;
  while (have_f && have_s) {
    const long kf = envelopeIndex(epsilon, f.tau), ks = envelopeIndex(epsilon, s.tau);
    if (kf < ks) {
      ++unmatched_full;
      have_f = next_full(f);
    } else if (ks < kf) {
      ++unmatched_slow;
      have_s = next_slow(s);
    } else {
      cmp.add(f, s);
      if (on_pair) on_pair(f, s);
      have_f = next_full(f);
      have_s = next_slow(s);
    }
  }
  while (have_f) ++unmatched_full, have_f = next_full(f);
  while (have_s) ++unmatched_slow, have_s = next_slow(s);
  ComparisonResult r = cmp.result();
  r.unmatched_full = unmatched_full;
  r.unmatched_slow = unmatched_slow;
  return r;
}

int metronomesOf(const std::vector<EnvelopeRow>& full, const std::vector<EnvelopeRow>& slow) {
  const EnvelopeRow* first = !full.empty()   ? &full.front()
                             : !slow.empty() ? &slow.front()
                                             : nullptr;
  if (!first) throw std::invalid_argument("compareEnvelopes: no rows to compare");
  return static_cast<int>(first->A.size());
}

RowSource rowSource(const std::vector<EnvelopeRow>& rows) {
  return [&rows, i = size_t{0}](EnvelopeRow& r) mutable {
    return i < rows.size() ? (r = rows[i++], true) : false;
  };
}

ComparisonResult compareEnvelopes(const std::vector<EnvelopeRow>& full,
                                  const std::vector<EnvelopeRow>& slow, double epsilon) {
  return joinEnvelopes(metronomesOf(full, slow), rowSource(full), rowSource(slow), epsilon);
}

}  // namespace metrosync
