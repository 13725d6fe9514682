#include "tools/bench/peer_verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "base/number_text.h"

namespace metrosync::bench {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// timeAtError's own tolerance at a front's ends (rounding of the error as written to CSV)
constexpr double kEndSlack = 1e-12;

double errorOf(const SidePoint& p, ErrorMeasure m) {
  return m == ErrorMeasure::FinalState ? p.err_final : p.err_envelope;
}

// The final-state error is compared on the runs without samples where they were timed.
double timeOf(const SidePoint& p, ErrorMeasure m, Clock c) {
  const double fin = c == Clock::Cpu ? p.cpu_final_s : p.wall_final_s;
  if (m == ErrorMeasure::FinalState && std::isfinite(fin)) return fin;
  return c == Clock::Cpu ? p.cpu_s : p.wall_s;
}

// "1e-04..1e-06, 1e-09" for the errors of the cells picked by `pick` (runs of neighbours joined)
template <class Pick>
std::string errorsWhere(const RatioRow& row, Pick pick) {
  std::string s;
  for (size_t k = 0; k < row.cells.size(); ++k) {
    if (!pick(row.cells[k])) continue;
    size_t last = k;
    while (last + 1 < row.cells.size() && pick(row.cells[last + 1])) ++last;
    s += (s.empty() ? "" : ", ") + errorLabel(row.cells[k].error) +
         (last > k ? ".." + errorLabel(row.cells[last].error) : "");
    k = last;
  }
  return s;
}

}  // namespace

std::string measureName(ErrorMeasure m) {
  return m == ErrorMeasure::FinalState ? "final-state" : "envelope";
}

std::string clockName(Clock c) {
  return c == Clock::Cpu ? "CPU" : "wall";
}

std::string errorLabel(double error) {
  std::string s = numberText(error, 1, Notation::Scientific);
  if (s.compare(1, 3, ".0e") == 0) s.erase(1, 2);
  return s;
}

std::vector<WorkPoint> sideFront(const std::vector<SidePoint>& points, ErrorMeasure m, Clock c) {
  std::vector<WorkPoint> pts;
  for (const SidePoint& p : points) pts.push_back({errorOf(p, m), timeOf(p, m, c)});
  return paretoFront(pts);
}

bool RatioCell::filled() const {
  return std::isfinite(ratio);
}

std::string coverageGap(const std::vector<WorkPoint>& front, double error, const std::string& who) {
  if (front.empty()) return who + " has no timed run";
  if (error < front.front().error * (1 - kEndSlack))
    return who + " does not reach it (its most accurate run: " +
           numberText(front.front().error, 1, Notation::Scientific) + ")";
  if (error > front.back().error * (1 + kEndSlack))
    return who + "'s cheapest run is already at " +
           numberText(front.back().error, 1, Notation::Scientific) +
           " (nothing looser measured: not extrapolated)";
  return "";
}

RatioCell equalErrorCell(const std::vector<WorkPoint>& ours, const std::vector<WorkPoint>& peer,
                         double error) {
  RatioCell cell;
  cell.error = error;
  cell.time_ours_s = timeAtError(ours, error);
  cell.time_peer_s = timeAtError(peer, error);
  cell.ratio = cell.time_peer_s / cell.time_ours_s;
  if (!cell.filled()) {
    const std::string a = coverageGap(ours, error, "metrosync");
    const std::string b = coverageGap(peer, error, "the peer");
    cell.reason = a.empty() ? b : b.empty() ? a : a + "; " + b;
  }
  return cell;
}

RatioTable ratioTable(const std::vector<VerdictScene>& scenes, ErrorMeasure m, Clock c,
                      const std::vector<double>& errors) {
  RatioTable t;
  t.measure = m;
  t.clock = c;
  t.errors = errors;
  std::vector<const VerdictScene*> order;
  for (const VerdictScene& s : scenes)
    if (!s.ours.empty() && (!s.peer.empty() || !s.peer_skipped.empty())) order.push_back(&s);
  std::stable_sort(order.begin(), order.end(), [](const VerdictScene* a, const VerdictScene* b) {
    return a->n < b->n || (a->n == b->n && a->name < b->name);
  });
  for (const VerdictScene* s : order) {
    RatioRow row;
    row.scene = s->name;
    row.n = s->n;
    row.skipped = s->peer.empty() ? s->peer_skipped : "";
    const auto fo = sideFront(s->ours, m, c), fp = sideFront(s->peer, m, c);
    for (double e : errors) {
      row.cells.push_back(equalErrorCell(fo, fp, e));
      if (!row.skipped.empty()) row.cells.back().reason = kPeerNotRun + (": " + row.skipped);
    }
    t.rows.push_back(row);
  }
  return t;
}

namespace {

// Adds one row's cells to `v` (the rows's own verdict when `v` starts empty).
void tally(const RatioRow& row, Verdict& v) {
  if (!row.skipped.empty()) return;
  for (const RatioCell& c : row.cells) {
    ++v.cells;
    if (!c.filled()) {
      ++v.empty;
    } else {
      if (c.ratio < kTargetRatio) ++v.below;
      if (!(c.ratio >= v.worst))
        v.worst = c.ratio, v.worst_at = row.scene + " at " + errorLabel(c.error);
    }
  }
  const auto low = [](const RatioCell& c) { return c.filled() && c.ratio < kTargetRatio; };
  const auto gap = [](const RatioCell& c) { return !c.filled(); };
  if (const std::string w = errorsWhere(row, low); !w.empty())
    v.below_where.push_back(row.scene + ": " + w);
  if (const std::string w = errorsWhere(row, gap); !w.empty())
    v.empty_where.push_back(row.scene + ": " + w);
}

}  // namespace

Verdict verdictOf(const RatioTable& t) {
  Verdict v;
  v.worst = kNaN;
  for (const RatioRow& row : t.rows) tally(row, v);
  v.met = v.cells > 0 && v.below == 0 && v.empty == 0;
  return v;
}

Verdict verdictOf(const RatioRow& row) {
  Verdict v;
  v.worst = kNaN;
  tally(row, v);
  v.met = v.cells > 0 && v.below == 0 && v.empty == 0;
  return v;
}

bool peerMeasured(const std::vector<VerdictScene>& scenes, ErrorMeasure m) {
  for (const VerdictScene& s : scenes)
    if (!sideFront(s.peer, m, Clock::Cpu).empty()) return true;
  return false;
}

double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> lx, ly;
  for (size_t k = 0; k < std::min(x.size(), y.size()); ++k)
    if (x[k] > 0 && y[k] > 0 && std::isfinite(x[k]) && std::isfinite(y[k]))
      lx.push_back(std::log(x[k])), ly.push_back(std::log(y[k]));
  if (lx.size() < 2) return kNaN;
  double mx = 0, my = 0;
  for (size_t k = 0; k < lx.size(); ++k) mx += lx[k], my += ly[k];
  mx /= static_cast<double>(lx.size());
  my /= static_cast<double>(ly.size());
  double sxy = 0, sxx = 0;
  for (size_t k = 0; k < lx.size(); ++k)
    sxy += (lx[k] - mx) * (ly[k] - my), sxx += (lx[k] - mx) * (lx[k] - mx);
  return sxx > 0 ? sxy / sxx : kNaN;
}

std::vector<SlopeRow> nSlope(const std::vector<VerdictScene>& scenes,
                             const std::vector<std::string>& slope_scenes,
                             const std::vector<double>& errors, ErrorMeasure m, Clock c) {
  std::vector<const VerdictScene*> used;
  for (const VerdictScene& s : scenes)
    if (std::find(slope_scenes.begin(), slope_scenes.end(), s.name) != slope_scenes.end() &&
        s.periods > 0)
      used.push_back(&s);
  std::stable_sort(used.begin(), used.end(),
                   [](const VerdictScene* a, const VerdictScene* b) { return a->n < b->n; });
  std::vector<SlopeRow> rows;
  if (used.empty()) return rows;
  for (double e : errors) {
    SlopeRow r;
    r.error = e;
    std::vector<double> ns;
    for (const VerdictScene* s : used) {
      r.scenes.push_back(s->name);
      r.ns.push_back(s->n);
      ns.push_back(s->n);
      r.ours_per_period_s.push_back(timeAtError(sideFront(s->ours, m, c), e) / s->periods);
      r.peer_per_period_s.push_back(timeAtError(sideFront(s->peer, m, c), e) / s->periods);
      r.peer_skipped.push_back(s->peer.empty() ? s->peer_skipped : "");
    }
    r.slope_ours = logLogSlope(ns, r.ours_per_period_s);
    r.slope_peer = logLogSlope(ns, r.peer_per_period_s);
    rows.push_back(r);
  }
  return rows;
}

bool Agreement::flagged() const {
  return !self && skipped.empty() && (!validated || !(err_final <= bound));
}

double agreementBound(const std::vector<double>& errors) {
  double b = kPeerAgreement;
  for (double e : errors)
    if (e > 0) b = std::min(b, e / kAgreementMargin);
  return b;
}

std::vector<Agreement> peerAgreement(const std::vector<VerdictScene>& scenes, const Sides& sides,
                                     double bound) {
  std::vector<Agreement> out;
  for (const VerdictScene& s : scenes) {
    const bool ref_ours = s.reference_engine == sides.ours;
    const bool ref_peer = s.reference_engine == sides.peer;
    bool any = false;
    for (const CrossCheck& cc : s.cross_checks) {
      const bool across =
          (ref_ours && cc.engine == sides.peer) || (ref_peer && cc.engine == sides.ours);
      const bool self = cc.engine == s.reference_engine;
      if (!across && !self) continue;
      Agreement a;
      a.scene = s.name;
      a.reference = s.reference;
      a.check = cc.method;
      a.validated = across;
      a.self = self;
      a.err_final = cc.err_final;
      a.err_envelope = cc.err_envelope;
      a.bound = bound;
      out.push_back(a);
      any = any || across;
    }
    // a scene the peer ran without a cross-check is not validated; one it could not run says
    // why; one where the peer was not asked for is not the validation's business
    if (!any && (!s.peer.empty() || !s.peer_skipped.empty())) {
      Agreement a;
      a.scene = s.name;
      a.reference = s.reference;
      a.skipped = s.peer.empty() ? s.peer_skipped : "";
      a.bound = bound;
      out.push_back(a);
    }
  }
  return out;
}

int fewestRuns(const std::vector<VerdictScene>& scenes) {
  int fewest = 0;
  for (const VerdictScene& s : scenes)
    for (const auto* side : {&s.ours, &s.peer})
      for (const SidePoint& p : *side)
        if (fewest == 0 || p.runs < fewest) fewest = p.runs;
  return fewest;
}

}  // namespace metrosync::bench
