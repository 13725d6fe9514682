#include "sim/analysis/regime.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <numeric>
#include <stdexcept>

#include "base/constants.h"
#include "base/number_text.h"

namespace metrosync {

const char* toString(Regime r) {
  switch (r) {
    case Regime::Death:
      return "death";
    case Regime::Suppression:
      return "suppression";
    case Regime::Drift:
      return "drift";
    case Regime::InPhase:
      return "in-phase";
    case Regime::Antiphase:
      return "antiphase";
    case Regime::PhaseLocked:
      return "phase-locked";
    case Regime::Unsettled:
      return "unsettled";
    case Regime::Uncoupled:
      return "uncoupled";
    case Regime::Alive:
      return "alive";
    case Regime::None:
      return "none";
    case Regime::Unknown:
      return "unknown";
  }
  return "unknown";
}

double wrapToPi(double angle_rad) {
  // remainder() gives [-pi, pi]; move -pi to +pi so the interval is (-pi, pi]
  double w = std::remainder(angle_rad, kTwoPi);
  if (w <= -kPi) w += kTwoPi;
  return w;
}

RegimeWindow::RegimeWindow(double tau_end, double epsilon, RegimeRules rules)
    : tau_end_(tau_end), min_tau_(rules.min_periods * kTwoPi * epsilon), rules_(rules) {
  if (!(epsilon > 0.0) || !std::isfinite(epsilon))
    throw std::invalid_argument("RegimeWindow: epsilon must be > 0");
  too_short_ = tau_end < min_tau_;
  tau_start_ = std::max(0.0, std::min((1.0 - rules.window_fraction) * tau_end, tau_end - min_tau_));
  settle_start_ = std::max(
      tau_start_,
      std::min(tau_end - rules.settle_fraction * (tau_end - tau_start_), tau_end - min_tau_));
}

void ValueRanges::add(const std::vector<double>& v) {
  if (lo.empty()) {
    lo = hi = v;
    return;
  }
  for (size_t k = 0; k < v.size() && k < lo.size(); ++k) {
    lo[k] = std::min(lo[k], v[k]);
    hi[k] = std::max(hi[k], v[k]);
  }
}

namespace {
// index of the pair (i, j), i < j < n, in row order
size_t pairIndex(size_t i, size_t j, size_t n) {
  return i * n - i * (i + 1) / 2 + (j - i - 1);
}
// phi_i - phi_j from a row's psi (psi_k = phi_1 - phi_k; psi_1 = 0)
double pairDifference(const std::vector<double>& psi, size_t i, size_t j) {
  const double pi_ = i == 0 ? 0.0 : psi[i - 1], pj = j == 0 ? 0.0 : psi[j - 1];
  return pj - pi_;
}
}  // namespace

void RegimeWindow::platformMode(int mode, double x) {
  run_x_min_ = std::min(run_x_min_, x);
  run_x_max_ = std::max(run_x_max_, x);
  if (in_window_) {
    x_min_ = std::min(x_min_, x);
    x_max_ = std::max(x_max_, x);
  }
  platform_seen_ = true;
  mode_now_ = mode;
  pending_slip_ = pending_slip_ || mode != 0;
}

void RegimeWindow::setEnvelopePlatform(const FrictionLaw& law) {
  envelope_platform_ = true;
  law_ = law;
}

namespace {
// the slow flow's platform in one envelope row: slips when the law cannot hold the averaged
// drive |Z| = r sum_j A_j (Coulomb: s = |Z| / mu > 1)
bool envelopeSlips(const EnvelopeRow& row, const FrictionLaw& law) {
  double sum = 0.0;
  for (double a : row.A) sum += a;
  const double r = std::isnan(row.r) ? orderParameter(row.A, row.psi) : row.r;
  return !law.holdsDrive(r * sum);
}
}  // namespace

std::vector<double> RegimeWindow::maxAmplitude() const {
  return rows_in_window_ == 0 ? last_.A : a_max_;
}

std::vector<double> RegimeWindow::minAmplitudeTau() const {
  return rows_in_window_ == 0 ? std::vector<double>(last_.A.size(), last_.tau) : a_min_tau_;
}

void RegimeWindow::add(const EnvelopeRow& row) {
  last_ = row;
  have_last_ = true;
  // the platform: the full model's own stick/slip when it reports it, else the averaged drive
  bool known = false, slipped = false;
  if (platform_seen_) {
    known = true;
    slipped = pending_slip_;
    pending_slip_ = mode_now_ != 0;
  } else if (envelope_platform_) {
    known = true;
    slipped = envelopeSlips(row, law_);
  }
  run_slip_rows_ += known && slipped;
  if (row.tau < tau_start_) return;
  in_window_ = true;
  platform_rows_ += known;
  slip_rows_ += known && slipped;
  const size_t n = row.psi.size() + 1;
  if (rows_in_window_ == 0) a_max_ = a_min_ = row.A, a_min_tau_.assign(row.A.size(), row.tau);
  for (size_t i = 0; i < row.A.size() && i < a_max_.size(); ++i) {
    a_max_[i] = std::max(a_max_[i], row.A[i]);
    if (row.A[i] <= a_min_[i]) a_min_[i] = row.A[i], a_min_tau_[i] = row.tau;
  }
  const bool settling = row.tau >= settle_start_;
  psi_.add(row.psi);
  if (settling) psi_settle_.add(row.psi);
  if (n >= 2) {  // every pair (for N = 2 the one pair is psi_2)
    std::vector<double> d;
    d.reserve(n * (n - 1) / 2);
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j) d.push_back(pairDifference(row.psi, i, j));
    pairs_.add(d);
    if (settling) pairs_settle_.add(d);
  }
  ++rows_in_window_;
}

double RegimeWindow::pairRangeIn(const ValueRanges& r, size_t i, size_t j) const {
  if (i == j || rows_in_window_ == 0) return 0.0;
  if (i > j) std::swap(i, j);
  return r.range(pairIndex(i, j, last_.psi.size() + 1));
}

std::vector<double> RegimeWindow::rangesOf(const ValueRanges& r) const {
  std::vector<double> range(last_.psi.size(), 0.0);
  if (rows_in_window_ == 0) return range;  // judged on the last row alone
  for (size_t j = 0; j < range.size(); ++j) range[j] = r.range(j);
  return range;
}

std::string regimeName(const RegimeVerdict& v) {
  return v.name.empty() ? toString(v.regime) : v.name;
}

std::string clusterText(const std::vector<int>& sizes) {
  std::string s;
  for (size_t k = 0; k < sizes.size();) {
    size_t run = 1;
    while (k + run < sizes.size() && sizes[k + run] == sizes[k]) ++run;
    const std::string size = std::to_string(sizes[k]);
    if (run >= 3) {
      s += (s.empty() ? "" : "+") + size + "x" + std::to_string(run);
    } else {
      for (size_t r = 0; r < run; ++r) s += (s.empty() ? "" : "+") + size;
    }
    k += run;
  }
  return s;
}

namespace {

// Clusters of the alive metronomes (see the header): members (0-based), largest first. Also says
// whether every alive pair is settled, whether some pair drifts, and whether every pair ends
// within in_phase_rad (in-phase for all, not by single linkage alone).
struct ClusterAnalysis {
  std::vector<std::vector<size_t>> members;
  std::vector<int> sizes;
  bool all_settled = true, any_drift = false, all_close = true;
};

// phase of metronome i relative to metronome 1 in the last row: phi_i - phi_1 = -psi_i
double relativePhase(const std::vector<double>& psi, size_t i) {
  return i == 0 ? 0.0 : -psi[i - 1];
}

ClusterAnalysis findClusters(const RegimeWindow& w, const std::vector<size_t>& alive) {
  ClusterAnalysis c;
  const RegimeRules& r = w.rules();
  const std::vector<double>& psi = w.last().psi;
  std::vector<size_t> parent(alive.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<size_t(size_t)> root = [&](size_t a) {
    return parent[a] == a ? a : parent[a] = root(parent[a]);
  };
  for (size_t a = 0; a < alive.size(); ++a)
    for (size_t b = a + 1; b < alive.size(); ++b) {
      const bool settled =
          r.settled(w.pairRange(alive[a], alive[b]), w.pairSettleRange(alive[a], alive[b]));
      c.all_settled = c.all_settled && settled;
      // drift: moved by more than drift_rad over the window and still moving at its end
      c.any_drift = c.any_drift || (!settled && w.pairRange(alive[a], alive[b]) > r.drift_rad);
      const bool close =
          std::fabs(wrapToPi(pairDifference(psi, alive[a], alive[b]))) <= r.in_phase_rad;
      c.all_close = c.all_close && close;
      if (settled && close) parent[root(a)] = root(b);
    }
  std::vector<std::vector<size_t>> groups(alive.size());
  for (size_t a = 0; a < alive.size(); ++a) groups[root(a)].push_back(alive[a]);
  for (auto& g : groups)
    if (!g.empty()) c.members.push_back(g);
  std::stable_sort(c.members.begin(), c.members.end(),
                   [](const auto& x, const auto& y) { return x.size() > y.size(); });
  for (const auto& g : c.members) c.sizes.push_back(static_cast<int>(g.size()));
  return c;
}

// Each cluster's mean phase (unit complex numbers averaged) minus the first cluster's.
std::vector<double> clusterPhases(const ClusterAnalysis& c, const std::vector<double>& psi) {
  std::vector<double> mean;
  for (const auto& g : c.members) {
    double re = 0.0, im = 0.0;
    for (size_t i : g) {
      re += std::cos(relativePhase(psi, i));
      im += std::sin(relativePhase(psi, i));
    }
    mean.push_back(std::atan2(im, re));
  }
  std::vector<double> d;
  for (double m : mean) d.push_back(wrapToPi(m - mean.front()));
  return d;
}

// a >= 3 alive metronomes, no two in one cluster: every gap between neighbouring phases within
// the splay tolerance of 2 pi / a
bool isSplay(const RegimeRules& r, const std::vector<size_t>& alive,
             const std::vector<double>& psi) {
  const size_t a = alive.size();
  if (a < 3) return false;
  std::vector<double> phase;
  for (size_t i : alive) phase.push_back(wrapToPi(relativePhase(psi, i)) + kPi);  // [0, 2 pi)
  std::sort(phase.begin(), phase.end());
  const double even = kTwoPi / static_cast<double>(a);
  const double tol = std::min(r.splay_rad, 0.25 * even);
  for (size_t k = 0; k < a; ++k) {
    const double gap = k + 1 < a ? phase[k + 1] - phase[k] : phase[0] + kTwoPi - phase[k];
    if (std::fabs(gap - even) > tol) return false;
  }
  return true;
}

// The N >= 3 name of the alive metronomes' state (at least two alive).
std::string aliveName(const ClusterAnalysis& c, bool splay) {
  if (c.sizes.size() == 1 && c.all_close) return "in-phase";
  // clusters locked to each other (groups that slide past each other are drift or unsettled)
  if (c.all_settled && c.sizes.size() > 1 && c.sizes.front() >= 2)
    return "clusters:" + clusterText(c.sizes);
  if (c.all_settled) return splay ? "splay" : "phase-locked";
  return c.any_drift ? "drift" : "unsettled";
}

}  // namespace

namespace {
// The phase rules on the judged psi_j (every metronome alive): drift, in-phase, antiphase,
// phase-locked, or unsettled with the reason.
// settled: every judged psi_j RegimeRules::settled (still over the window, or over its settling
// part after a transient that ended); drift:
// not settled, some psi_j moved by more than drift_rad over the whole window and still moves.
// range, settle: (N-1 x 1) the ranges over the window and over its settling part.
Regime phaseRegime(const RegimeRules& r, const EnvelopeRow& last, const std::vector<double>& range,
                   const std::vector<double>& settle, const std::vector<size_t>& judged,
                   std::string& reason) {
  bool moved = false, settled = true, in_phase = true, antiphase = true;
  double widest = 0.0;
  for (size_t k : judged) {
    const bool still = r.settled(range[k], settle[k]);
    moved = moved || (range[k] > r.drift_rad && !still);
    settled = settled && still;
    widest = std::max(widest, settle[k]);
    in_phase = in_phase && std::fabs(wrapToPi(last.psi[k])) <= r.in_phase_rad;
    antiphase = antiphase && std::fabs(wrapToPi(last.psi[k] - kPi)) <= r.antiphase_rad;
  }
  if (settled && in_phase) return Regime::InPhase;
  if (settled && antiphase) return Regime::Antiphase;
  if (settled) return Regime::PhaseLocked;
  if (moved) return Regime::Drift;
  reason = "the phase differences still move over the window's last part (range up to " +
           numberText(widest, 4) + " rad; settled needs < " + numberText(r.settled_rad, 4) +
           " there and at most " + numberText(r.ended_ratio, 4) + " of the window's range, or < " +
           numberText(r.settled_rad, 4) + " over the window; drift > " +
           numberText(r.drift_rad, 4) + " over the window)";
  return Regime::Unsettled;
}

// The platform over the window and, when it never slipped there, over the run before it
// (v.platform_*): `uncoupled` is a platform that never slipped in the run. A platform that the
// metronomes' drive moved and that stuck later (the slow flow near antiphase sticks once the drive
// falls below friction, psi frozen near pi) is judged by the phase rules, whether it stuck before
// the window or within it (docs/regimes.md).
void judgePlatform(const RegimeWindow& w, RegimeVerdict& v) {
  if (w.platformRows() == 0 || w.platformRows() != w.rowsInWindow()) return;
  // full model: slips that leave the platform where it was (micro-slips) do not count
  auto moved = [&](double travel) { return travel < 0 || travel > w.rules().still_platform; };
  v.platform_slipped = w.slipRows() > 0 && moved(w.platformTravel()) ? 1 : 0;
  v.platform_slip_rows = w.platformTravel() < 0 ? -1 : w.slipRows();
  v.platform_travel = w.platformTravel();
  if (v.platform_slipped == 0)
    v.platform_slipped_before = w.runSlipRows() > w.slipRows() && moved(w.runTravel()) ? 1 : 0;
}

std::string tooShortReason(const RegimeWindow& w) {
  return "the run is shorter than " + numberText(w.rules().min_periods, 4) +
         " fast periods (tau_end = " + numberText(w.tauEnd(), 4) + " < " +
         numberText(w.rules().min_periods, 4) +
         " * 2 pi epsilon = " + numberText(w.minimumTau(), 4) + "): too short to judge";
}
}  // namespace

RegimeVerdict classifyRegime(const RegimeWindow& window, const std::vector<double>& theta_c,
                             const std::vector<bool>& locked) {
  RegimeVerdict v;
  if (window.empty()) return v;  // Unknown
  const EnvelopeRow& last = window.last();
  const size_t n = last.A.size();
  if (theta_c.size() != n)
    throw std::invalid_argument("classifyRegime: " + std::to_string(theta_c.size()) +
                                " critical angles for " + std::to_string(n) + " metronomes");
  if (!locked.empty() && locked.size() != n)
    throw std::invalid_argument("classifyRegime: locked mask has the wrong size");
  auto isLocked = [&](size_t i) { return !locked.empty() && locked[i]; };

  v.window_rows = window.rowsInWindow();
  v.window_tau_start = window.tauStart();
  v.psi_range = window.psiRange();
  v.psi_settle_range = window.psiSettleRange();
  v.settle_tau_start = window.settleTauStart();
  for (double p : last.psi) v.psi_final.push_back(wrapToPi(p));

  // a non-finite state has no regime (only a failed run ends like that)
  for (double a : last.A)
    if (!std::isfinite(a)) return v;
  for (double p : last.psi)
    if (!std::isfinite(p)) return v;

  // death and suppression: below the escapement's critical angle throughout the window
  const std::vector<double> a_max = window.maxAmplitude();
  int swinging = 0, dead = 0;
  v.alive.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    if (isLocked(i)) continue;
    ++swinging;
    v.alive[i] = a_max[i] >= theta_c[i] ? 1 : 0;
    dead += v.alive[i] == 0;
  }
  judgePlatform(window, v);
  const RegimeRules& r = window.rules();
  v.dead = dead;
  std::vector<size_t> alive_idx;
  for (size_t i = 0; i < n; ++i)
    if (v.alive[i] == 1) alive_idx.push_back(i);
  const ClusterAnalysis clusters = findClusters(window, alive_idx);
  v.cluster_sizes = clusters.sizes;
  for (const auto& g : clusters.members) {
    v.cluster_members.emplace_back();
    for (size_t i : g) v.cluster_members.back().push_back(static_cast<int>(i) + 1);
  }
  if (!clusters.members.empty()) v.cluster_phase = clusterPhases(clusters, last.psi);
  const bool uncoupled = v.platform_slipped == 0 && v.platform_slipped_before == 0;
  // the name: the enum's, or for three or more swinging metronomes the clusters'
  auto named = [&](Regime regime) {
    v.regime = regime;
    v.name = toString(regime);
    if (swinging < 3 || regime == Regime::Death) return v;
    const std::string suppressed = dead > 0 ? "suppressed:" + std::to_string(dead) : "";
    if (alive_idx.size() < 2)
      v.name = suppressed;
    else
      v.name = suppressed + (suppressed.empty() ? "" : ";") +
               (uncoupled ? std::string(toString(Regime::Uncoupled))
                          : aliveName(clusters, isSplay(r, alive_idx, last.psi)));
    return v;
  };
  if (swinging == 0) return named(Regime::None);
  if (window.tooShort()) {
    v.reason = tooShortReason(window);
    v.undecided = true;
    v.regime = Regime::Unsettled;
    v.name = toString(Regime::Unsettled);
    return v;
  }
  // a metronome above theta_c in the window, below it at the end and at its lowest there is
  // dying, neither dead nor alive yet: the run has not reached its final state. (One whose
  // amplitude swings through theta_c and back, an exchange of energy between the metronomes, was
  // lower earlier in the window: it is alive, and the phase rules judge the state.)
  const std::vector<double> lowest_at = window.minAmplitudeTau();
  for (size_t i = 0; i < n; ++i)
    if (v.alive[i] == 1 && last.A[i] < theta_c[i] && lowest_at[i] >= last.tau) {
      v.reason = "metronome " + std::to_string(i + 1) +
                 " falls below theta_c within the window (dying): a longer run decides";
      v.undecided = true;
      v.regime = Regime::Unsettled;
      v.name = toString(Regime::Unsettled);
      return v;
    }
  if (dead == swinging) return named(Regime::Death);
  if (dead > 0) return named(Regime::Suppression);

  // phase rules on psi_j = phi_1 - phi_j, j = 2..N (index j-2), both pendulums swinging
  std::vector<size_t> judged;
  if (!isLocked(0))
    for (size_t j = 1; j < n; ++j)
      if (!isLocked(j) && j - 1 < last.psi.size()) judged.push_back(j - 1);
  if (judged.empty()) return named(Regime::Alive);
  if (uncoupled) return named(Regime::Uncoupled);
  const Regime phase = phaseRegime(r, last, v.psi_range, v.psi_settle_range, judged, v.reason);
  return named(phase);
}

RegimeVerdict classifyRegime(const std::vector<EnvelopeRow>& rows, double tau_end, double epsilon,
                             const std::vector<double>& theta_c, const std::vector<bool>& locked,
                             RegimeRules rules) {
  RegimeWindow w(tau_end, epsilon, rules);
  for (const auto& row : rows) w.add(row);
  return classifyRegime(w, theta_c, locked);
}

}  // namespace metrosync
