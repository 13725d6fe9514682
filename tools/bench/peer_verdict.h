// The verdict against the peer (issues 11 and 23), as values: for each scene, the ratio peer time
// / metrosync time at equal error (each side's front: its cheapest run at each error over all its
// integrators, log-log interpolation between measured points, never extrapolation), a verdict per
// scene and overall, the cost per fast period against N with its log-log slope, and the guards
// that make a table a result (medians of enough runs, the peer validated against metrosync at
// tight tolerance, far below the errors compared). The peer is the careful one (engine "peer",
// tools/bench/careful_peer.h) unless Sides says otherwise. At equal final-state error each side
// is timed on its runs without samples (integration and events only), at equal envelope error on
// its runs that record the envelope. No I/O here: the Markdown and CSV are written by
// tools/bench/peer_verdict_report.h, read back by tools/bench/wp_csv.h.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "tools/bench/bench_metrics.h"

namespace metrosync::bench {

// The target: metrosync at least this many times faster than the peer at equal error.
constexpr double kTargetRatio = 2.0;
// The bound on the peer's agreement with metrosync at tight tolerance (final state).
constexpr double kPeerAgreement = 1e-8;
// ... and "far below the compared errors": at least this factor below the smallest error of the
// ratio table (so that neither side's error is the other's difference from the reference).
constexpr double kAgreementMargin = 10.0;
// The target of the N-slope of metrosync's cost per fast period (issue 23: ~N^1.0-1.1).
constexpr double kSlopeTargetLow = 1.0, kSlopeTargetHigh = 1.1;
// Fewer timed runs behind a median than this and the ratio table is not a result (the issue asks
// for medians of >= 5 runs).
constexpr int kMinRunsForResult = 5;

// The reason of every cell of a scene the peer was not run on starts with this.
inline constexpr const char* kPeerNotRun = "the peer was not run";

enum class ErrorMeasure { FinalState, Envelope };
enum class Clock { Cpu, Wall };
std::string measureName(ErrorMeasure m);  // "final-state" | "envelope"
std::string clockName(Clock c);           // "CPU" | "wall"
std::string errorLabel(double error);     // "1e-04" for a decade, "2.5e-05" otherwise

// One timed work-precision point (status "ok") of one engine.
struct SidePoint {
  std::string method;  // engine:integrator:setting
  double err_final = 0.0, err_envelope = 0.0;
  double cpu_s = 0.0, wall_s = 0.0;  // medians of the runs recording the envelope
  int runs = 0;                      // timed runs behind the medians
  // medians of the runs without samples (NaN: not measured; cpu_s and wall_s stand in)
  double cpu_final_s = std::numeric_limits<double>::quiet_NaN();
  double wall_final_s = std::numeric_limits<double>::quiet_NaN();
  // `metrosync run`'s points: the medians of engine_seconds and of wall_seconds / engine_seconds
  double engine_s = std::numeric_limits<double>::quiet_NaN();
  double wall_over_engine = std::numeric_limits<double>::quiet_NaN();
};

// A run at tight tolerance checked against the scene's reference.
struct CrossCheck {
  std::string engine, method;  // method: engine:integrator:setting
  double err_final = 0.0, err_envelope = 0.0;
};

// What the verdict needs of one scene's work-precision run.
struct VerdictScene {
  std::string name;
  int n = 0;             // metronomes
  double periods = 0.0;  // fast periods in the run
  std::string reference_engine, reference;
  std::vector<SidePoint> ours, peer;  // metrosync's direct engine, the peer
  std::vector<SidePoint> run;         // `metrosync run` itself (tools/bench/run_method.h)
  std::string peer_skipped;           // why the peer was not run on this scene ("" if it was)
  // engine:integrator, in order seen
  std::vector<std::string> our_methods, peer_methods, run_methods;
  std::vector<CrossCheck> cross_checks;
  // 1-minute load over the timed points of both sides (NaN: not recorded)
  double load_min = std::numeric_limits<double>::quiet_NaN();
  double load_max = std::numeric_limits<double>::quiet_NaN();
};

// The two sides' engine names.
struct Sides {
  std::string ours = "direct", peer = "peer";
  std::string run = "run";  // `metrosync run`, timed against the peer beside the engine
};

// A side's front on one error measure and clock.
std::vector<WorkPoint> sideFront(const std::vector<SidePoint>& points, ErrorMeasure m, Clock c);

// One cell: the ratio at `error`, or NaN and why not.
struct RatioCell {
  double error = 0.0;
  double time_ours_s = 0.0, time_peer_s = 0.0;  // NaN where the side's front does not cover it
  double ratio = 0.0;                           // peer / ours; NaN when either is missing
  std::string reason;                           // why the cell is empty ("" when it is not)
  bool filled() const;
};

// Why a front does not cover `error` ("" when it does), naming the side as `who`.
std::string coverageGap(const std::vector<WorkPoint>& front, double error, const std::string& who);

RatioCell equalErrorCell(const std::vector<WorkPoint>& ours, const std::vector<WorkPoint>& peer,
                         double error);

struct RatioRow {
  std::string scene;
  int n = 0;
  std::vector<RatioCell> cells;  // one per error of the table
  std::string skipped;  // the peer was not run on this scene, and why (the cells are empty)
};

struct RatioTable {
  ErrorMeasure measure = ErrorMeasure::FinalState;
  Clock clock = Clock::Cpu;
  std::vector<double> errors;
  std::vector<RatioRow> rows;  // by N, then name
};

// Scenes without points on both sides are left out, but for those where the peer was not run:
// a skipped row with the reason.
RatioTable ratioTable(const std::vector<VerdictScene>& scenes, ErrorMeasure m, Clock c,
                      const std::vector<double>& errors);

// Met when every cell is filled and at least kTargetRatio. Skipped rows do not count.
struct Verdict {
  bool met = false;
  int cells = 0, below = 0, empty = 0;
  double worst = 0.0;  // smallest filled ratio (NaN when none)
  std::string worst_at;
  std::vector<std::string> below_where;  // "n128: 1e-04, 1e-05"
  std::vector<std::string> empty_where;
};
Verdict verdictOf(const RatioTable& t);
// One scene's verdict (its row alone).
Verdict verdictOf(const RatioRow& row);
// Does the peer's front cover any error at all on this measure (false: the peer reports no such
// error, e.g. the careful peer and the envelope)?
bool peerMeasured(const std::vector<VerdictScene>& scenes, ErrorMeasure m);

// Least-squares slope of log(y) against log(x) over the pairs where both are positive and
// finite; NaN with fewer than two distinct x.
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

// Cost per fast period on each side's front at one error, over the N-scaling scenes.
struct SlopeRow {
  double error = 0.0;
  std::vector<std::string> scenes;
  std::vector<int> ns;
  std::vector<double> ours_per_period_s, peer_per_period_s;  // NaN where not covered
  std::vector<std::string> peer_skipped;      // per scene: why the peer was not run ("" if it was)
  double slope_ours = 0.0, slope_peer = 0.0;  // NaN with < 2 points
};

// `slope_scenes`: the names of the scenes that differ only in N, in any order (the ones present
// are used, sorted by N).
std::vector<SlopeRow> nSlope(const std::vector<VerdictScene>& scenes,
                             const std::vector<std::string>& slope_scenes,
                             const std::vector<double>& errors, ErrorMeasure m, Clock c);

// The peer's validation on one scene: a cross-check of one side against a reference on the
// other. `validated` is false (with nothing else set) when the scene has none. A cross-check on
// the reference's own engine is listed too, as `self`: the reference's own uncertainty, the
// scale against which a peer's difference is read (never flagged, never a validation).
// `bound`: the final-state difference a validation must stay within (agreementBound).
struct Agreement {
  std::string scene, reference, check;
  bool validated = false, self = false;
  std::string skipped;  // the peer was not run on this scene, and why (never flagged)
  double err_final = 0.0, err_envelope = 0.0;
  double bound = kPeerAgreement;
  bool flagged() const;  // a validation above `bound` in final state, or none at all
};
// kPeerAgreement, or kAgreementMargin below the smallest of `errors` if that is tighter.
double agreementBound(const std::vector<double>& errors);
std::vector<Agreement> peerAgreement(const std::vector<VerdictScene>& scenes, const Sides& sides,
                                     double bound = kPeerAgreement);

// The fewest timed runs behind any point of either side (0 when there is none).
int fewestRuns(const std::vector<VerdictScene>& scenes);

}  // namespace metrosync::bench
