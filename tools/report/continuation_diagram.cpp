#include "tools/report/continuation_diagram.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/number_text.h"

namespace metrosync {

// Tableau 10: distinct on screen and in print, none of them black (the special points' colour).
const char* const kBranchColours[10] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                        "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

namespace {

using continuation::ContinuationResult;
using continuation::ResultPoint;
using continuation::ResultSpecial;

// Open markers and widths per metronome: the first metronome's line widest, so that a curve
// drawn over it (the same amplitude) leaves its edges showing.
constexpr int kMarkers[] = {6, 8, 4, 12, 10};
constexpr int kMarkersPerBranch = 12;  // markers along a branch: enough to tell, few enough to read

std::string plotNumber(double v) {
  return std::isfinite(v) ? numberText(v, 10) : std::string("nan");  // gnuplot: no inf
}

const char* colour(int k) {
  return kBranchColours[k % 10];
}

int marker(int i) {
  return kMarkers[i % 5];
}

double width(int i) {
  return std::max(1.0, 4.0 - 1.2 * i);
}

std::string row(const ResultPoint& q, bool stable) {
  std::ostringstream d;
  d << plotNumber(q.value);
  for (double a : q.A) d << " " << plotNumber(a);
  for (double p : q.psi) d << " " << plotNumber(p);
  d << " " << (stable ? 1 : 0) << "\n";
  return d.str();
}

// Whether x lies between a and b (either order), within a hair for rounding.
bool between(double x, double a, double b) {
  const double hair = 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
  return x >= std::min(a, b) - hair && x <= std::max(a, b) + hair;
}

// The special point of branch b located on the step from a to q (its parameter and amplitudes
// between theirs), nullptr when there is none.
const ResultPoint* specialOnStep(const ContinuationResult& r, int b, const ResultPoint& a,
                                 const ResultPoint& q) {
  for (const ResultSpecial& s : r.special) {
    if (s.at.branch != b || !between(s.at.value, a.value, q.value)) continue;
    bool inside = true;
    for (size_t i = 0; i < q.A.size() && inside; ++i) inside = between(s.at.A[i], a.A[i], q.A[i]);
    if (inside) return &s.at;
  }
  return nullptr;
}

// A branch's rows in order, each a point and the stability it is written with: where stability
// changes, the solid and the dashed line meet at the special point located on that step (a Hopf
// point, a fold...), else at the new point: it is written once with the old stability, then with
// the new.
std::vector<std::pair<const ResultPoint*, bool>> branchRows(const ContinuationResult& r, int b) {
  std::vector<std::pair<const ResultPoint*, bool>> rows;
  const ResultPoint* prev = nullptr;
  for (const ResultPoint& q : r.points) {
    if (q.branch != b) continue;
    if (prev && prev->stable != q.stable) {
      const ResultPoint* at = specialOnStep(r, b, *prev, q);
      rows.push_back({at ? at : &q, prev->stable});
      if (at) rows.push_back({at, q.stable});
    }
    rows.push_back({&q, q.stable});
    prev = &q;
  }
  return rows;
}

// The datablock of branch b's column col of row() (2..N+1: A_i, N+2..2N: psi_j): its rows as
// KEY, the value, the value where stable (else NaN), the value where unstable. One small block
// per curve, no expression in `using`: gnuplot reads every column of each row it draws from and
// sets up its signal handlers for every expression it evaluates, and 32 metronomes on 34
// branches make 6400 curves.
std::string branchBlock(size_t b, int col) {
  return "$b" + std::to_string(b) + "c" + std::to_string(col);
}

std::string branchColumn(const std::vector<std::pair<const ResultPoint*, bool>>& rows, int col) {
  std::ostringstream d;
  for (const auto& [q, stable] : rows) {
    const size_t k = static_cast<size_t>(col - 2);
    const std::string v = plotNumber(k < q->A.size() ? q->A[k] : q->psi[k - q->A.size()]);
    d << plotNumber(q->value) << " " << v << " " << (stable ? v : "nan") << " "
      << (stable ? "nan" : v) << "\n";
  }
  return d.str();
}

// `rows` as the datablock `name` ("nan" when empty: one column, as gnuplot 5.4 crashes on a
// datablock of NaN points drawn as labels).
void datablock(std::ostringstream& d, const std::string& name, const std::string& rows) {
  d << name << " << EOD\n" << (rows.empty() ? "nan\n" : rows) << "EOD\n";
}

std::string label(const ResultSpecial& s) {
  if (s.type == "fold") return "LP";
  if (s.type == "branch") return "BP";
  if (s.type == "border") return "B";
  if (std::isnan(s.lyapunov)) return "H";
  return s.lyapunov > 0 ? "H(sub)" : "H(sup)";
}

std::string specialRows(const ContinuationResult& r) {
  std::ostringstream d;
  for (const ResultSpecial& s : r.special) {
    std::string line = row(s.at, true);
    line.pop_back();
    d << line << " " << label(s) << " "
      << plotNumber(*std::max_element(s.at.A.begin(), s.at.A.end())) << "\n";
  }
  return d.str();
}

// KEY, then lo_k hi_k for each k.
std::string rangeRow(double value, const std::vector<double>& lo, const std::vector<double>& hi) {
  std::string d = plotNumber(value);
  for (size_t k = 0; k < lo.size(); ++k) d += " " + plotNumber(lo[k]) + " " + plotNumber(hi[k]);
  return d;
}

std::string familyRows(const continuation::ResultFamily& f) {
  std::string d;
  for (const auto& q : f.points) d += rangeRow(q.value, q.psi_min, q.psi_max) + "\n";
  return d;
}

std::string cycleRows(const continuation::ResultCycle& c) {
  std::string d;
  for (const auto& q : c.points)
    d += rangeRow(q.value, q.A_min, q.A_max) + " " + (q.stable ? "1" : "0") + "\n";
  return d;
}

// The confirmed folds of cycles: KEY, the largest A_max.
std::string cycleFoldRows(const ContinuationResult& r) {
  std::ostringstream d;
  for (const auto& c : r.cycles)
    for (const auto& f : c.folds)
      if (f.confirmed)
        d << plotNumber(f.at.value) << " "
          << plotNumber(*std::max_element(f.at.A_max.begin(), f.at.A_max.end())) << "\n";
  return d.str();
}

// The branch a cycle's Hopf point lies on (its colour).
int cycleBranch(const ContinuationResult& r, double hopf) {
  for (const ResultSpecial& s : r.special)
    if (s.type == "hopf" && std::abs(s.at.value - hopf) <= 1e-9 * std::max(1.0, std::abs(hopf)))
      return s.at.branch;
  return 0;
}

long branchPoints(const ContinuationResult& r, int b) {
  return std::count_if(r.points.begin(), r.points.end(),
                       [b](const ResultPoint& q) { return q.branch == b; });
}

// One curve per branch, stable and unstable: column `col` of its rows (the i-th metronome's);
// its markers shifted along the branch by i / N of their interval, so that coinciding curves
// show every metronome's.
void branchCurves(const ContinuationResult& r, int col, int i, int count, std::ostringstream& p) {
  for (size_t b = 0; b < r.branches.size(); ++b) {
    const long every = std::max(1L, branchPoints(r, static_cast<int>(b)) / kMarkersPerBranch);
    for (int s : {1, 0})
      p << branchBlock(b, col) << " using 1:" << (s ? 3 : 4) << " with lines lc rgb '"
        << colour(static_cast<int>(b)) << "' lw " << width(i) << " dt " << (s ? 1 : 2)
        << " notitle, \\\n  ";
    p << branchBlock(b, col) << " every " << every << "::" << i * every / std::max(1, count)
      << " using 1:2 with points lc rgb '" << colour(static_cast<int>(b)) << "' pt " << marker(i)
      << " ps 0.8 notitle, \\\n  ";
  }
}

// The cycles' max and min of A_i.
void cycleCurves(const ContinuationResult& r, int i, std::ostringstream& p) {
  const int stable = 2 * r.metronomes + 2;
  for (size_t c = 0; c < r.cycles.size(); ++c)
    for (int col : {2 + 2 * i, 3 + 2 * i})
      for (int s : {1, 0})
        p << "$cycle" << c << " using 1:(column(" << stable << ")==" << s << " ? column(" << col
          << ") : NaN) with lines lc rgb '" << colour(cycleBranch(r, r.cycles[c].hopf_value))
          << "' lw 1 dt " << (s ? 1 : 2) << " notitle, \\\n  ";
}

void legend(const ContinuationResult& r, const std::string& name, int count, std::ostringstream& p,
            bool branches) {
  for (size_t b = 0; b < r.branches.size() && branches; ++b)
    p << "NaN with lines lc rgb '" << colour(static_cast<int>(b)) << "' lw 3 title 'branch " << b
      << (r.branches[b].neutral ? " (family)" : "") << "', \\\n  ";
  for (int i = 0; i < count; ++i)
    p << "NaN with linespoints lc rgb 'black' lw " << width(i) << " pt " << marker(i) << " title '"
      << name << "_" << i + (name == "A" ? 1 : 2) << "', \\\n  ";
  p << "NaN with lines lc rgb 'black' dt 1 title 'stable', NaN with lines lc rgb 'black' dt 2 "
       "title 'unstable'";
  if (!r.cycles.empty() && branches)
    p << ", NaN with lines lc rgb 'black' lw 1 title 'cycles: max, min A_i'";
  p << "\n";
}

std::string amplitudePanel(const ContinuationResult& r) {
  const int n = r.metronomes;
  std::ostringstream p;
  p << "set ylabel 'A_i'\nplot ";
  for (int i = 0; i < n; ++i) branchCurves(r, 2 + i, i, n, p);
  for (int i = 0; i < n; ++i) cycleCurves(r, i, p);
  for (int i = 0; i < n; ++i)
    p << "$special using 1:" << 2 + i << " with points pt 7 ps 1.0 lc rgb 'black' notitle, \\\n  ";
  p << "$special using 1:" << 2 * n + 3 << ":" << 2 * n + 2
    << " with labels offset 0,0.8 font ',9' notitle, \\\n  "
    << "$lpc using 1:2 with points pt 6 ps 1.4 lc rgb 'black' notitle, \\\n  "
    << "$lpc using 1:2:('LPC') with labels offset 0,0.8 font ',9' notitle, "
       "\\\n  ";
  legend(r, "A", n, p, true);
  return p.str();
}

std::string phasePanel(const ContinuationResult& r) {
  const int n = r.metronomes;
  std::ostringstream p;
  p << "set ylabel 'psi_j = phi_1 - phi_j'\nplot ";
  for (size_t f = 0; f < r.families.size(); ++f)
    for (int j = 0; j < n - 1; ++j)
      p << "$family" << f << " using 1:" << 2 + 2 * j << ":" << 3 + 2 * j
        << " with filledcurves lc rgb '" << colour(r.families[f].branch)
        << "' fs transparent solid 0.25 noborder notitle, \\\n  ";
  for (int j = 0; j < n - 1; ++j) branchCurves(r, 2 + n + j, j, n - 1, p);
  for (int j = 0; j < n - 1; ++j)
    p << "$special using 1:" << 2 + n + j
      << " with points pt 7 ps 1.0 lc rgb 'black' notitle, \\\n  ";
  legend(r, "psi", n - 1, p, false);
  return p.str();
}

}  // namespace

std::string continuationDiagramData(const ContinuationResult& r) {
  std::ostringstream d;
  for (size_t b = 0; b < r.branches.size(); ++b) {
    const auto rows = branchRows(r, static_cast<int>(b));
    for (int col = 2; col <= 2 * r.metronomes; ++col)
      datablock(d, branchBlock(b, col), branchColumn(rows, col));
  }
  datablock(d, "$special", specialRows(r));
  for (size_t f = 0; f < r.families.size(); ++f)
    datablock(d, "$family" + std::to_string(f), familyRows(r.families[f]));
  for (size_t c = 0; c < r.cycles.size(); ++c)
    datablock(d, "$cycle" + std::to_string(c), cycleRows(r.cycles[c]));
  datablock(d, "$lpc", cycleFoldRows(r));
  return d.str();
}

std::string continuationDiagramScript(const ContinuationResult& r, const std::string& data,
                                      const std::string& png) {
  const int n = r.metronomes;
  std::ostringstream g;
  g << "set terminal pngcairo size 1100," << (n > 1 ? 950 : 520) << " font ',11'\n"
    << "set output '" << png << "'\n"
    << "load '" << data << "'\n"
    << "set key outside right top\nset grid\n"
    // the same margins on both panels, so that their parameter axes line up whatever the keys
    << "set lmargin at screen 0.08\nset rmargin at screen 0.78\n"
    << "set multiplot layout " << (n > 1 ? 2 : 1) << ",1 title 'locked states of the slow flow "
    << "against " << r.param
    << ": stable solid, unstable dashed; LP fold, H(sub)/H(sup) Hopf, BP branch point, B border' "
       "noenhanced\n"
    << "set xlabel '" << r.param << "' noenhanced\n"
    << amplitudePanel(r);
  if (n > 1) g << phasePanel(r);
  g << "unset multiplot\n";
  return g.str();
}

}  // namespace metrosync
