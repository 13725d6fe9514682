#include "tools/cli/sweep_point_run.h"

#include <cmath>
#include <limits>

#include "base/number_text.h"
#include "sim/analysis/network_verdict.h"
#include "sim/analysis/regime.h"
#include "tools/cli/commands.h"
#include "tools/cli/engines.h"
#include "tools/cli/fault_hooks.h"
#include "tools/cli/network_sweep.h"
#include "tools/cli/sweep_summary.h"
#include "tools/report/outputs.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

// The model --model asks for: as given, else the --engine's, else the slow flow.
std::string requestedModel(const SweepOptions& opt) {
  if (!opt.model.empty()) return opt.model;
  return opt.engine.empty() ? "slow" : "";
}

// Is the rig text a network of platforms? Decided once per thread for the text it last saw: every
// point of a sweep (and every basin sample) has the same text, and parsing it once more per point
// cost 1.5% of a slow-flow point (docs/bench/sweep-throughput.md). --set and --vary cannot make a
// text a network: only the text's own `platforms` key does (yaml/network_loader.h).
bool isNetworkRig(const std::string& text) {
  thread_local std::string last_text;
  thread_local bool known = false, last = false;
  if (!known || text != last_text) {
    last = isNetworkText(text);
    last_text = text;
    known = true;
  }
  return last;
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

// Keeps what the verdict needs; a stop request (SIGINT, SIGTERM) interrupts the run.
struct PointSink : RunSink, PointJudge {
  PointSink(double tau_end, double epsilon) : window(tau_end, epsilon) {}
  void envelopeRow(const EnvelopeRow& row) override {
    window.add(row);
    if (keep) kept.push_back(formatEnvelopeRow(row));
    if (FileSink::stopRequested()) throw RunInterrupted(row.tau, "interrupted by a signal");
  }
  // the platform column (0 stuck): the `uncoupled` rule (full model)
  void trajectoryRow(const std::vector<double>& row) override {
    if (row.size() > 2) window.platformMode(static_cast<int>(row.back()), row[1] / x_unit);
  }
  void eventRow(const char*, const std::vector<double>& row) override { trajectoryRow(row); }
  void poll(double t) override {
    if (FileSink::stopRequested()) throw RunInterrupted(t, "interrupted by a signal");
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
  double x_unit = 1.0;  // trajectory x per scaled x
  bool keep = false;    // --keep envelope
  std::vector<std::string> kept;
};

// A network's verdict (sim/analysis/network_verdict.h) that a stop request interrupts, as
// PointSink does a rig's.
struct NetworkPointSink : NetworkVerdict, PointJudge {
  using NetworkVerdict::NetworkVerdict;
  void stateSample(double t, const std::vector<double>& y,
                   const std::vector<PlatformMode>& modes) override {
    NetworkVerdict::stateSample(t, y, modes);
    poll(t);
  }
  void poll(double t) override {
    if (FileSink::stopRequested()) throw RunInterrupted(t, "interrupted by a signal");
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
};

// Runs a point's rig or network through `run`, with the test hook (tools/cli/fault_hooks.h): a
// failed simulation is a failed report; nullopt when a stop request interrupted it.
template <class Run>
std::optional<RunReport> guardedRun(const PointInput& in, long g, Run run) {
  RunReport rep;
  try {
    if (const std::optional<std::string> why = injectedFailure(g))
      throw SimulationFailure{0.0, *why};
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
  if (!rep.complete && FileSink::stopRequested()) return std::nullopt;
  return rep;
}

// One point's run, a single rig's or a network's (a single rig is the network of one): the
// engine runs it into the judge's sink, which then judges it.
std::optional<PointOutcome> runPointModel(const PointInput& in, long g, PointJudge& judge) {
  std::optional<RunReport> rep = guardedRun(in, g, [&] {
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

std::string sweepRigText(const SweepOptions& opt) {
  // the same checks as every command: a regular file of bounded size (yaml/rig_loader.h)
  if (opt.rig_text) return *opt.rig_text;
  return opt.rig_path.empty() ? defaultRigYaml() : readRigFile(opt.rig_path);
}

std::string displayName(const SweepOptions& opt) {
  return opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
}

// The rig of one point: the base rig, --set, then the point's KEY=VALUE (a wildcard key
// "metronomes.*.REST" set at each of the n metronomes); checked like `run` checks its rig.
// `where` names the point ("grid point 12 (...)"); throws RigError naming it.
PointInput loadPointRig(const std::string& text, const SweepOptions& opt,
                        const std::vector<std::string>& point, const std::string& where,
                        const std::string& source) {
  std::vector<std::string> overrides = opt.sets;
  overrides.insert(overrides.end(), point.begin(), point.end());
  PointInput in;
  try {
    if (isNetworkRig(text))
      in.net = loadPlatformsNetwork(text, displayName(opt), overrides, engineLoadOptions(HUGE_VAL));
    in.rig = in.net ? networkSweepRig(*in.net) : loadRigText(text, displayName(opt), overrides);
  } catch (const RigError& e) {
    // the loader calls every override --set; the point's own ones come from --vary
    std::string what = e.what();
    for (const auto& o : point)
      for (size_t at = what.find("--set " + o); at != std::string::npos;
           at = what.find("--set " + o, at))
        what.replace(at, 6 + o.size(), source + " " + o);
    throw RigError(what + "\n  at " + where);
  }
  if (in.net) {  // docs/networks.md
    in.engine = &chooseEngine(opt.engine, opt.model, *in.net, displayName(opt), "sweeps");
    return in;
  }
  // checks --engine against --model and the point's integrator
  in.engine = &chooseEngine(opt.engine, requestedModel(opt), in.rig, displayName(opt));
  try {
    in.scaled = computeScaled(in.rig);
  } catch (const std::invalid_argument& e) {
    throw RigError(displayName(opt) + ": " + e.what() + "\n  at " + where);
  }
  return in;
}

PointInput loadPoint(const std::string& text, const SweepOptions& opt, const SweepGrid& grid,
                     long g) {
  const std::vector<std::string> point = grid.overrides(g);
  return loadPointRig(text, opt, point,
                      "grid point " + std::to_string(g) + " (" + joined(point) + ") of the sweep");
}

std::optional<SweepPoint> runPoint(const PointInput& in, long g, bool keep) {
  const ScaledParams& sp = in.scaled;
  std::optional<PointSink> sink;  // a single rig's (a network's verdict is its own sink)
  std::optional<NetworkPointSink> verdict;
  if (in.net) {
    verdict.emplace(*in.net);
  } else {
    sink.emplace(sp.tau_end, sp.epsilon);
    // the `uncoupled` rule: the slow flow's averaged drive, the full model's own stick/slip
    if (in.engine->model() != "full") sink->window.setEnvelopePlatform(sp.friction);
    sink->x_unit = in.rig.units == Units::Physical ? sp.x_scale_m : 1.0;
    sink->keep = keep;
  }
  const double engine_cpu0 = threadCpuSeconds();
  std::optional<PointOutcome> o =
      runPointModel(in, g, in.net ? static_cast<PointJudge&>(*verdict) : *sink);
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

std::pair<std::string, std::string> checkSweepPoint(const std::string& rig_text,
                                                    const SweepOptions& opt,
                                                    const std::vector<std::string>& point, int n,
                                                    const std::string& where) {
  const PointInput in = loadPointRig(rig_text, opt, point, where, "the drawn");
  if (static_cast<int>(in.rig.metronomes.size()) != n)
    throw UsageError(joined(point) + " changes the number of metronomes (at " + where + ")");
  return {in.engine->model(), in.engine->name()};
}

std::optional<SweepPoint> runSweepPointAt(const std::string& rig_text, const SweepOptions& opt,
                                          const std::vector<std::string>& point, int n,
                                          long index) {
  std::optional<PointInput> in;
  try {
    in = loadPointRig(rig_text, opt, point, "point " + std::to_string(index));
  } catch (const std::exception& e) {
    return unloadablePoint(index, n, e.what());
  }
  if (static_cast<int>(in->rig.metronomes.size()) != n)
    return unloadablePoint(index, n, "the point changes the number of metronomes");
  return runPoint(*in, index, false);  // basin samples: no envelope kept
}

}  // namespace metrosync::cli
