#include "sim/analysis/sweep_point.h"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "base/number_text.h"
#include "base/thread_cpu_time.h"
#include "sim/analysis/network_verdict.h"
#include "sim/analysis/order_parameter.h"
#include "sim/analysis/regime.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"

namespace metrosync {

namespace {

bool stopped(const PointHooks& h) {
  return h.stop && h.stop();
}

// ---- one point ---------------------------------------------------------------------------------

// What a point's run leaves for its row: the report, the last envelope row (none when the run
// never sampled), and, when it completed, its label and clusters.
struct PointOutcome {
  RunReport report;
  std::optional<EnvelopeRow> last;
  std::string regime, clusters;
};

// A point's sink and judge, one interface for a single rig's (PointSink) and a network's
// (NetworkPointSink): the run streams into sink(); judge() then fills the outcome's last row and,
// when the run completed, its label and clusters.
struct PointJudge {
  virtual ~PointJudge() = default;
  virtual RunSink& sink() = 0;
  virtual void judge(const PointInput& in, PointOutcome& o) const = 0;
};

// Keeps what the verdict needs; a stop request (the hooks') interrupts the run.
struct PointSink : RunSink, PointJudge {
  PointSink(double tau_end, double epsilon, const PointHooks& h)
      : window(tau_end, epsilon), hooks(h) {}
  void envelopeRow(const EnvelopeRow& row) override {
    window.add(row);
    if (keep) kept.push_back(formatEnvelopeRow(row));
    if (stopped(hooks)) throw RunInterrupted(row.tau, "interrupted by a signal");
  }
  // the platform column (0 stuck): the `uncoupled` rule (full model)
  void trajectoryRow(const std::vector<double>& row) override {
    if (row.size() > 2) window.platformMode(static_cast<int>(row.back()), row[1] / x_unit);
  }
  void eventRow(const char*, const std::vector<double>& row) override { trajectoryRow(row); }
  void poll(double t) override {
    if (stopped(hooks)) throw RunInterrupted(t, "interrupted by a signal");
  }
  RunSink& sink() override { return *this; }
  // its regime (SPEC 4) and clusters
  void judge(const PointInput& in, PointOutcome& o) const override {
    o.last = window.empty() ? o.report.final_row : window.last();
    if (!o.report.complete) return;
    const RegimeVerdict v = classifyRegime(window, in.scaled.theta_c, in.scaled.locked);
    o.regime = regimeName(v);
    o.clusters = clusterText(v.cluster_sizes);
  }
  RegimeWindow window;
  const PointHooks& hooks;
  double x_unit = 1.0;  // trajectory x per scaled x
  bool keep = false;    // --keep envelope
  std::vector<std::string> kept;
};

// A network's verdict (sim/analysis/network_verdict.h) that a stop request interrupts, as
// PointSink does a rig's.
struct NetworkPointSink : NetworkVerdict, PointJudge {
  NetworkPointSink(const Network& net, const PointHooks& h) : NetworkVerdict(net), hooks(h) {}
  void stateSample(double t, const std::vector<double>& y,
                   const std::vector<PlatformMode>& modes) override {
    NetworkVerdict::stateSample(t, y, modes);
    poll(t);
  }
  void poll(double t) override {
    if (stopped(hooks)) throw RunInterrupted(t, "interrupted by a signal");
  }
  RunSink& sink() override { return *this; }
  // the network's label (docs/sweep-points.md), each platform's regime
  void judge(const PointInput& in, PointOutcome& o) const override {
    if (!empty()) o.last = last();
    if (!o.report.complete) return;
    o.regime = label();
    const std::vector<std::string> regimes = platformRegimes();
    for (std::size_t q = 0; q < regimes.size(); ++q)
      o.clusters += (q ? "|" : "") + in.net->platforms[q].name + "=" + regimes[q];
  }
  const PointHooks& hooks;
};

// Runs a point's rig or network through `run`, with the hooks' fault (tests): a failed
// simulation is a failed report; nullopt when a stop request interrupted it.
template <class Run>
std::optional<RunReport> guardedRun(const PointInput& in, long g, const PointHooks& hooks,
                                    Run run) {
  RunReport rep;
  try {
    if (hooks.fault)
      if (const std::optional<std::string> why = hooks.fault(g)) throw SimulationFailure{0.0, *why};
    rep = run();
  } catch (const RunInterrupted&) {
    return std::nullopt;
  } catch (const SimulationFailure& f) {
    rep.complete = false;
    rep.failure = "stopped at t = " + numberText(f.t) +
                  (in.rig.units == Units::Physical ? " s" : "") + ": " + f.why;
  } catch (const std::exception& e) {
    rep.complete = false;
    rep.failure = e.what();
  }
  // an engine that turned the interruption into a failed report
  if (!rep.complete && stopped(hooks)) return std::nullopt;
  return rep;
}

// One point's run, a single rig's or a network's (a single rig is the network of one): the
// engine runs it into the judge's sink, which then judges it.
std::optional<PointOutcome> runPointModel(const PointInput& in, long g, const PointHooks& hooks,
                                          PointJudge& judge) {
  std::optional<RunReport> rep = guardedRun(in, g, hooks, [&] {
    return in.net ? in.engine->run(*in.net, judge.sink()) : in.engine->run(in.rig, judge.sink());
  });
  if (!rep) return std::nullopt;
  PointOutcome o{std::move(*rep), std::nullopt, "", ""};
  judge.judge(in, o);
  return o;
}

// s = |Z| / mu = r sum_j A_j / mu of a Coulomb platform (mu the kinetic coefficient, with or
// without mu_static); NaN, no value, for another law and for mu = 0 (no threshold)
double driveStrength(const FrictionLaw& law, const EnvelopeRow& last, double r) {
  const std::optional<double> mu = law.value("mu");
  if (!mu || !(*mu > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (double a : last.A) sum += a;
  return r * sum / *mu;
}

}  // namespace

std::optional<SweepPoint> runPoint(const PointInput& in, long g, const PointHooks& hooks) {
  const ScaledParams& sp = in.scaled;
  std::optional<PointSink> sink;  // a single rig's (a network's verdict is its own sink)
  std::optional<NetworkPointSink> verdict;
  if (in.net) {
    verdict.emplace(*in.net, hooks);
  } else {
    sink.emplace(sp.tau_end, sp.epsilon, hooks);
    // the `uncoupled` rule: the slow flow's averaged drive, the full model's own stick/slip
    if (in.engine->model() != "full") sink->window.setEnvelopePlatform(sp.friction);
    sink->x_unit = in.rig.units == Units::Physical ? sp.x_scale_m : 1.0;
    sink->keep = hooks.keep_envelope;
  }
  const double engine_cpu0 = threadCpuSeconds();
  std::optional<PointOutcome> o =
      runPointModel(in, g, hooks, in.net ? static_cast<PointJudge&>(*verdict) : *sink);
  if (!o) return std::nullopt;

  const int n = static_cast<int>(in.rig.metronomes.size());
  SweepPoint p;
  p.index = g;
  p.complete = o->report.complete;
  // the engine's run with the sink it streams into (a rig's envelope window, a network's verdict)
  p.engine_cpu_seconds = threadCpuSeconds() - engine_cpu0;
  if (o->last && static_cast<int>(o->last->A.size()) == n &&
      static_cast<int>(o->last->psi.size()) == n - 1) {
    const EnvelopeRow& last = *o->last;
    p.A = last.A;
    for (double v : last.psi) p.psi.push_back(wrapToTwoPi(v));
    p.r = std::isnan(last.r) ? orderParameter(last.A, last.psi) : last.r;
    p.tau = last.tau;
    if (!in.net) p.s = driveStrength(sp.friction, last, p.r);
  } else {
    p.A.assign(n, std::nan(""));
    p.psi.assign(n > 0 ? n - 1 : 0, std::nan(""));
  }
  if (o->report.complete) {
    p.regime = o->regime;
    p.clusters = o->clusters;
  } else {
    p.regime = "failed";
    p.message = o->report.failure.empty() ? "the run stopped early" : o->report.failure;
  }
  if (sink) p.kept_rows = std::move(sink->kept);
  return p;
}

// A grid point that could not even be loaded (checkGrid loads only the grid's corners): failed,
// with the loader's message, and the sweep goes on.
SweepPoint unloadablePoint(long g, int n, const std::string& why) {
  SweepPoint p;
  p.index = g;
  p.complete = false;
  p.regime = "failed";
  p.message = why;
  p.engine_cpu_seconds = 0.0;  // no engine ran
  p.A.assign(n, std::nan(""));
  p.psi.assign(n > 0 ? n - 1 : 0, std::nan(""));
  return p;
}

}  // namespace metrosync
