#include "sim/analysis/compare.h"

#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "sim/record/atomic_file.h"
#include "sim/analysis/regime.h"

namespace metrosync {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// Keeps the largest |d| and where it occurred; a NaN, once seen, sticks (it means a broken row).
void updateMax(double d, double tau, double& max, double& tau_at) {
  if (std::isnan(max)) return;
  if (std::isnan(d) || d > max) {
    max = d;
    tau_at = tau;
  }
}

void appendNumber(std::string& s, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, ",%.12g", v);
  s += buf;
}

// Merge-join of two row streams on the grid index; `next` returns false at the end.
using RowSource = std::function<bool(EnvelopeRow&)>;

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

ComparisonResult joinAndWrite(int n, RowSource next_full_all, RowSource next_slow_all,
                              double epsilon, const std::string& out_csv) {
  RowSource next_full = gridRowsOf(std::move(next_full_all), epsilon);
  RowSource next_slow = gridRowsOf(std::move(next_slow_all), epsilon);
  EnvelopeComparator cmp(n);
  AtomicFile out(out_csv);
  out.writeLine(cmp.header());
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
      out.writeLine(cmp.add(f, s));
      have_f = next_full(f);
      have_s = next_slow(s);
    }
  }
  while (have_f) ++unmatched_full, have_f = next_full(f);
  while (have_s) ++unmatched_slow, have_s = next_slow(s);
  out.commit();
  ComparisonResult r = cmp.result();
  r.unmatched_full = unmatched_full;
  r.unmatched_slow = unmatched_slow;
  return r;
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

std::string EnvelopeComparator::header() const {
  std::string h = "tau";
  for (int i = 1; i <= result_.n; ++i) {
    const std::string a = ",A_" + std::to_string(i);
    h += a + "_full" + a + "_slow";
  }
  for (int j = 2; j <= result_.n; ++j) {
    const std::string p = ",psi_" + std::to_string(j);
    h += p + "_full" + p + "_slow";
  }
  return h;
}

std::string EnvelopeComparator::add(const EnvelopeRow& full, const EnvelopeRow& slow) {
  const size_t n = static_cast<size_t>(result_.n);
  if (full.A.size() != n || slow.A.size() != n || full.psi.size() != n - 1 ||
      slow.psi.size() != n - 1)
    throw std::invalid_argument("EnvelopeComparator: rows of the wrong width");
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", full.tau);
  std::string line = buf;
  for (size_t i = 0; i < n; ++i) {
    appendNumber(line, full.A[i]);
    appendNumber(line, slow.A[i]);
    updateMax(std::fabs(full.A[i] - slow.A[i]), full.tau, result_.max_abs_dA[i],
              result_.tau_max_dA[i]);
  }
  for (size_t j = 0; j + 1 < n; ++j) {
    appendNumber(line, full.psi[j]);
    appendNumber(line, slow.psi[j]);
    // modulo 2 pi: the two unwrapped phases may be on branches a multiple of 2 pi apart
    updateMax(std::fabs(wrapToPi(full.psi[j] - slow.psi[j])), full.tau, result_.max_abs_dpsi[j],
              result_.tau_max_dpsi[j]);
  }
  ++result_.rows;
  return line;
}

long envelopeIndex(double epsilon, double tau) {
  return std::lround(tau / (epsilon * kTwoPi) - 0.5);
}

EnvelopeCsvReader::EnvelopeCsvReader(const std::string& path) : path_(path), in_(path) {
  if (!in_) throw std::runtime_error(path + ": cannot open");
  std::string header;
  if (!std::getline(in_, header)) throw std::runtime_error(path + ": empty file");
  layout_ = parseEnvelopeHeader(header, path);  // with or without the r column
  n_ = layout_.n;
}

bool EnvelopeCsvReader::next(EnvelopeRow& row) {
  std::string line;
  while (std::getline(in_, line)) {
    ++lineno_;
    if (line.empty()) continue;
    std::vector<double> v;
    v.reserve(layout_.columns());
    size_t start = 0;
    while (start <= line.size()) {
      const size_t comma = line.find(',', start);
      const std::string cell =
          line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      try {
        size_t used = 0;
        v.push_back(std::stod(cell, &used));
      } catch (const std::exception&) {
        throw std::runtime_error(path_ + ":" + std::to_string(lineno_) + ": bad number '" + cell +
                                 "'");
      }
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (static_cast<int>(v.size()) != layout_.columns())
      throw std::runtime_error(path_ + ":" + std::to_string(lineno_) + ": wrong number of columns");
    row = envelopeRowFromValues(v, layout_);
    return true;
  }
  return false;
}

ComparisonResult compareEnvelopes(const std::vector<EnvelopeRow>& full,
                                  const std::vector<EnvelopeRow>& slow, double epsilon,
                                  const std::string& out_csv) {
  const EnvelopeRow* first = !full.empty()   ? &full.front()
                             : !slow.empty() ? &slow.front()
                                             : nullptr;
  if (!first) throw std::invalid_argument("compareEnvelopes: no rows to compare");
  size_t i = 0, k = 0;
  return joinAndWrite(
      static_cast<int>(first->A.size()),
      [&](EnvelopeRow& r) { return i < full.size() ? (r = full[i++], true) : false; },
      [&](EnvelopeRow& r) { return k < slow.size() ? (r = slow[k++], true) : false; }, epsilon,
      out_csv);
}

ComparisonResult compareEnvelopeFiles(const std::string& full_csv, const std::string& slow_csv,
                                      double epsilon, const std::string& out_csv) {
  EnvelopeCsvReader full(full_csv), slow(slow_csv);
  if (full.n() != slow.n())
    throw std::runtime_error(full_csv + " has " + std::to_string(full.n()) + " metronomes, " +
                             slow_csv + " has " + std::to_string(slow.n()));
  return joinAndWrite(
      full.n(), [&](EnvelopeRow& r) { return full.next(r); },
      [&](EnvelopeRow& r) { return slow.next(r); }, epsilon, out_csv);
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
