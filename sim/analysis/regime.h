// Regime classification (SPEC section 4 and issues 15, 37; docs/regimes.md), judged on the
// envelope rows of the last 10% of the run (in tau) but never fewer than 5 fast periods: the window
// is
//   tau >= max(0, min(0.9 tau_end, tau_end - 5 * 2 pi epsilon)),
// and a run shorter than 5 fast periods (tau_end < 5 * 2 pi epsilon) is `unsettled`, with the
// reason in RegimeVerdict::reason. The window's settling part is its last half (at least 5 fast
// periods, at most the whole window). "Settled" (RegimeRules::settled) means varying by < 0.1 rad
// over the window, or over the settling part when that moved by at most a quarter of the window's
// range (a transient that ended), so that a transient ending inside the window is not taken for
// the state the run ends in, nor a steady creep for a settled state. Metronome 1 is the reference.
// A metronome is dead when A_i stays below theta_c,i throughout the window (its largest A_i there
// is < theta_c,i). The platform is judged as RegimeWindow::platformMode / setEnvelopePlatform say.
// Rules, in order:
//   death         every metronome dead
//   suppression   at least one dead and at least one alive
//   uncoupled     all alive, the platform never slips in the run (neither in the window nor
//                 before it: coupling never moved it)
//   in-phase      all alive, every psi_j settled and ending within 0.2 rad of 0 mod 2 pi
//   antiphase     as in-phase, but every psi_j ends within 0.5 rad of pi (mod 2 pi)
//   phase-locked  every psi_j settled, elsewhere
//   drift         all alive, not settled, and some psi_j moves by more than pi over the window
//   unsettled     none of the above
// "Moves by" and "varies by" both mean the range (max - min) of the unwrapped psi_j (over the
// window, or over its settling part), so a phase slip is caught wherever it happens. A platform
// that slipped and then stuck (before the window or within it) is judged by the phase rules: its
// phase difference stays where coupling brought it.
//
// Extensions of the SPEC (it is silent on these cases):
//   - N = 1 (no phase difference): `death` when the metronome is dead, `alive` otherwise.
//   - locked metronomes (pendulum held in its box, SPEC 1a) are neither dead nor alive: they are
//     left out of every rule, and so are the psi_j that involve them (all of them when metronome 1
//     is locked). With one swinging metronome left the verdict is `death`/`alive` as for N = 1;
//     with none, `none`.
//   - a run that stopped early (complete: false) has no verdict: `unknown` (chosen by the caller).
//   - a window with no row (rows that stop before it: a run cut short) is judged on the last row.
//
// Names for N >= 3 swinging metronomes (RegimeVerdict::name; the enum keeps the rules above for
// every N). Two alive metronomes i, j are in one cluster when phi_i - phi_j is settled and ends
// within 0.2 rad of 0 (mod 2 pi): the in-phase rule, pair by pair;
// clusters are the connected groups (single linkage). With d dead and a alive metronomes:
//   death                     every metronome dead
//   uncoupled                 the platform never slips in the run
//   in-phase                  one cluster of all alive, every pair within 0.2 rad
//   clusters:S1+S2+...        several clusters, at least one of two or more, every pair settled
//                             (sizes descending, single metronomes counted as 1: clusters:3+1+1;
//                             three or more of one size as SIZExCOUNT: clusters:2+1x14)
//   splay                     no two in one cluster, every pair settled, the phases evenly spread
//                             (every gap within min(splay_rad, 0.25 * 2 pi / a) of 2 pi / a)
//   phase-locked              no two in one cluster, every pair settled, not evenly spread
//   drift                     not all settled, some unsettled pair's difference moves by more
//                             than pi over the window
//   unsettled                 none of these
// and with d > 0 dead among them, `suppressed:d` alone (one alive) or before the name of the alive
// ones: suppressed:2;in-phase, suppressed:1;uncoupled. For N <= 2 the name is the enum's.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "base/constants.h"
#include "contact/friction_law.h"
#include "sim/record/envelope.h"

namespace metrosync {

enum class Regime {
  Death,
  Suppression,
  Drift,
  InPhase,
  Antiphase,
  PhaseLocked,
  Unsettled,
  Uncoupled,  // every swinging metronome alive and the platform never slips in the window
  Alive,      // N = 1 (or one swinging metronome), alive
  None,       // no swinging metronome at all
  Unknown,    // not judged (the run stopped early)
};

// The name written to summary.json and regimes.csv: "death", "in-phase", "phase-locked", ...
const char* toString(Regime r);

// SPEC 4 thresholds (radians) and window; named so that tests and sweeps can refer to them.
struct RegimeRules {
  double window_fraction = 0.1;  // judged on tau >= (1 - window_fraction) * tau_end ...
  // ... but on at least this many fast periods (2 pi epsilon each in tau): a phase settled to
  // 0.1 rad must show it over several periods, and the full model's period averages need a few
  // rows to vary at all
  double min_periods = 5.0;
  double drift_rad = kPi;    // drift: range of some psi_j > this
  double settled_rad = 0.1;  // settled: range of every psi_j < this (settled() below)
  // the settling part: the window's last settle_fraction (but at least min_periods fast periods,
  // at most the whole window). Settled is judged there, so that a transient that ends inside the
  // window (a phase slip into antiphase, the board sticking) is not taken for the state the run
  // ended in; drift (still moving) is judged over the whole window (docs/regimes.md)
  double settle_fraction = 0.5;
  // ... but only for a transient that ended: the settling part moved by at most this fraction of
  // what the whole window moved. A phase slip or a board that sticks in the window's first half
  // leaves the last half nearly still (0.011 of 4.4 rad on the flagship map); a creep at a steady
  // rate moves the last half by half the window's range, and a longer run's longer window sees it
  // move more (hard/n100.yaml in the full model: judged on the last half alone its clusters looked
  // settled at its tau = 2 and not at 3)
  double ended_ratio = 0.25;
  // settled: still over the whole window, or a transient that ended before the settling part
  bool settled(double window_range, double settle_range) const {
    return window_range < settled_rad ||
           (settle_range < settled_rad && settle_range <= ended_ratio * window_range);
  }
  double in_phase_rad = 0.2;   // |final psi_j - 0| (mod 2 pi) <= this
  double antiphase_rad = 0.5;  // |final psi_j - pi| (mod 2 pi) <= this
  // splay (N >= 3): every gap between neighbouring phases within this of 2 pi / a (a alive), but
  // never more than a quarter of 2 pi / a
  double splay_rad = 0.2;
  // full model: slips in the window that move the platform by at most this (scaled x, range over
  // the window) do not count for `uncoupled`. Near-simultaneous ticks in antiphase give
  // micro-slips of 3e-9 (experiment-high-friction-antiphase, which die out over hundreds of
  // periods); a coupled antiphase platform travels 0.02 (paper/f4.2); docs/regimes.md.
  double still_platform = 1e-6;
};

// An angle moved by a multiple of 2 pi into (-pi, pi].
double wrapToPi(double angle_rad);

// The smallest and largest value of each of a few quantities over the rows added.
struct ValueRanges {
  std::vector<double> lo, hi;
  void add(const std::vector<double>& v);
  // max - min of quantity k (0 when nothing was added)
  double range(size_t k) const { return k < lo.size() ? hi[k] - lo[k] : 0.0; }
};

// Streams envelope rows and keeps only what the rules need (memory independent of the run
// length): per psi_j its min, max over the window and over its settling part, the same for every
// pair phi_i - phi_j (N >= 3), and the last row.
class RegimeWindow {
 public:
  // epsilon: the rig's scaled epsilon (a fast period is 2 pi epsilon in tau)
  RegimeWindow(double tau_end, double epsilon, RegimeRules rules = {});

  void add(const EnvelopeRow& row);

  // The platform (the `uncoupled` rule). Full model: platformMode() takes the platform column
  // (0 stuck, +-1 sliding) and the position x in scaled units of every trajectory row and every
  // event; a row counts as slipping when the platform slid at any such call since the previous
  // row (or was sliding at it). Slow flow (no trajectory rows): with the rig's friction law set
  // by setEnvelopePlatform, a row slips when the law cannot hold the averaged drive
  // |sum_j A_j e^{i phi_j}| (FrictionLaw::holdsDrive: Coulomb holds while it is <= mu; viscous and
  // none never hold, fixed always). Without either: never `uncoupled`.
  void platformMode(int mode, double x_scaled);
  void setEnvelopePlatform(const FrictionLaw& law);
  long platformRows() const { return platform_rows_; }  // window rows with the platform known
  long slipRows() const { return slip_rows_; }          // ... and the platform slipping
  long runSlipRows() const { return run_slip_rows_; }   // rows of the whole run that slip
  // full model: max - min of the platform's scaled x over the window (-1: no trajectory row)
  double platformTravel() const {
    return platform_seen_ && x_max_ >= x_min_ ? x_max_ - x_min_ : -1.0;
  }
  // full model: the same over the whole run, from its start (-1: no trajectory row)
  double runTravel() const {
    return platform_seen_ && run_x_max_ >= run_x_min_ ? run_x_max_ - run_x_min_ : -1.0;
  }
  // (N x 1) the largest A_i over the window (the last row's when the window has no row)
  std::vector<double> maxAmplitude() const;
  // (N x 1) the tau of the smallest A_i over the window (its last row when the window has none)
  std::vector<double> minAmplitudeTau() const;

  double tauStart() const { return tau_start_; }
  double settleTauStart() const { return settle_start_; }  // the settling part: tau >= this
  double tauEnd() const { return tau_end_; }
  // the run spans fewer than rules().min_periods fast periods: too short to judge
  bool tooShort() const { return too_short_; }
  double minimumTau() const { return min_tau_; }  // min_periods * 2 pi epsilon
  long rowsInWindow() const { return rows_in_window_; }
  bool empty() const { return !have_last_; }
  const EnvelopeRow& last() const { return last_; }
  // (N-1 x 1) max - min of each unwrapped psi_j over the window (0 when judged on one row)
  std::vector<double> psiRange() const { return rangesOf(psi_); }
  // ... over the settling part
  std::vector<double> psiSettleRange() const { return rangesOf(psi_settle_); }
  // max - min of phi_i - phi_j over the window (0-based i != j; 0 when judged on one row)
  double pairRange(size_t i, size_t j) const { return pairRangeIn(pairs_, i, j); }
  // ... over the settling part
  double pairSettleRange(size_t i, size_t j) const { return pairRangeIn(pairs_settle_, i, j); }
  const RegimeRules& rules() const { return rules_; }

 private:
  std::vector<double> rangesOf(const ValueRanges& r) const;
  double pairRangeIn(const ValueRanges& r, size_t i, size_t j) const;

  double tau_start_ = 0.0, tau_end_ = 0.0, min_tau_ = 0.0, settle_start_ = 0.0;
  bool too_short_ = false;
  RegimeRules rules_;
  long rows_in_window_ = 0;
  bool have_last_ = false;
  EnvelopeRow last_;
  ValueRanges psi_, psi_settle_;  // (N-1 x 1) over the window, over its settling part
  // (N (N-1)/2 x 1) phi_i - phi_j = psi_j - psi_i (psi_1 = 0), pairs i < j in row order
  ValueRanges pairs_, pairs_settle_;
  std::vector<double> a_max_;              // (N x 1) over the window
  std::vector<double> a_min_, a_min_tau_;  // (N x 1) the smallest A_i over the window, and when
  // platform: seen in trajectory rows/events; slid since the last envelope row; sliding now
  bool platform_seen_ = false, pending_slip_ = false;
  int mode_now_ = 0;
  bool envelope_platform_ = false;
  FrictionLaw law_;  // scaled
  long platform_rows_ = 0, slip_rows_ = 0, run_slip_rows_ = 0;
  bool in_window_ = false;  // a row of the window has come
  double x_min_ = HUGE_VAL, x_max_ = -HUGE_VAL;
  double run_x_min_ = HUGE_VAL, run_x_max_ = -HUGE_VAL;
};

struct RegimeVerdict {
  Regime regime = Regime::Unknown;
  std::vector<int> alive;                // (N x 1) 1 alive, 0 dead, -1 locked (not judged)
  std::vector<double> psi_range;         // (N-1 x 1) max - min over the window, rad
  std::vector<double> psi_settle_range;  // (N-1 x 1) ... over the window's settling part
  std::vector<double> psi_final;         // (N-1 x 1) final psi_j wrapped to (-pi, pi]
  long window_rows = 0;                  // rows with tau in the window (0: judged on the last row)
  double window_tau_start = 0.0;         // the window is tau >= this
  double settle_tau_start = 0.0;  // its settling part (RegimeRules::settle_fraction) tau >= this
  // what regimes.csv and summary.json call it (set by classifyRegime): toString(regime), or for
  // N >= 3 swinging metronomes the cluster name above; read it through regimeName()
  std::string name;
  std::vector<int> cluster_sizes;  // clusters of the alive metronomes, largest first
  int dead = 0;                    // swinging metronomes that are dead
  // the alive metronomes' clusters (1-based numbers), the largest first, and each cluster's mean
  // phase minus the first cluster's, wrapped to (-pi, pi] (summary.json: regime_window.clusters)
  std::vector<std::vector<int>> cluster_members;
  std::vector<double> cluster_phase;
  // the platform over the window: -1 unknown, 0 never slipped, 1 slipped
  int platform_slipped = -1;
  // when it never slipped in the window (platform_slipped == 0): whether it slipped before, in
  // the run up to the window (1: coupling moved it, then it stuck; 0: it never moved: uncoupled);
  // -1 otherwise
  int platform_slipped_before = -1;
  long platform_slip_rows = -1;   // full model: window rows in which the platform slid
  double platform_travel = -1.0;  // full model: range of the platform's scaled x over the window
  // why the verdict is `unsettled` or `unknown` (empty otherwise), in words for summary.json
  std::string reason;
  // `unsettled` because the run ended before its state could be judged (shorter than
  // min_periods fast periods, or a metronome dying in the window): a longer run decides
  bool undecided = false;
};

// The verdict's name: `name`, or toString(regime) for a verdict not made by classifyRegime.
std::string regimeName(const RegimeVerdict& v);

// "3+2+1", "2+1x14" (a size repeated three times or more); empty when none is alive.
std::string clusterText(const std::vector<int>& sizes);

// Applies the rules to what `window` saw. theta_c: (N x 1) scaled critical angles; locked:
// (N x 1) or empty (none locked). An empty window (no row at all) gives Regime::Unknown.
RegimeVerdict classifyRegime(const RegimeWindow& window, const std::vector<double>& theta_c,
                             const std::vector<bool>& locked = {});

// Convenience for whole runs held in memory (tests, small comparisons).
RegimeVerdict classifyRegime(const std::vector<EnvelopeRow>& rows, double tau_end, double epsilon,
                             const std::vector<double>& theta_c,
                             const std::vector<bool>& locked = {}, RegimeRules rules = {});

}  // namespace metrosync
