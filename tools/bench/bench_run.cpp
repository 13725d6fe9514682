#include "tools/bench/bench_run.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "base/constants.h"
#include "sim/analysis/regime.h"
#include "sim/engines/engine.h"
#include "tools/bench/careful_peer.h"
#include "tools/bench/odeint_peer.h"
#include "tools/bench/run_method.h"
#include "tools/bench/scaled_state.h"
#include "tools/bench/siconos_peer.h"
#include "yaml/rig_loader.h"

namespace metrosync::bench {

namespace {

// Thrown by the sink to abandon a run that exceeds its budget. Not a std::exception, so that the
// engines' own handlers (which turn std::exception into complete = false) let it through.
struct OverBudget {};

// Keeps the envelope rows only (or, for Sampling::FinalState, asks for no samples at all); stops
// the run when the wall-clock budget is spent.
class BenchSink : public RunSink {
 public:
  BenchSink(double budget_s, Sampling sampling)
      : budget_s_(budget_s),
        envelope_(sampling == Sampling::Envelope),
        start_(std::chrono::steady_clock::now()) {}
  bool wantsEventRows() const override { return false; }   // as the peer, which builds none
  bool wantsTrajectory() const override { return false; }  // the final state comes in the report
  bool wantsEnvelope() const override { return envelope_; }
  void envelopeRow(const EnvelopeRow& row) override {
    rows.push_back(row);
    if (budget_s_ > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() >
            budget_s_)
      throw OverBudget{};
  }
  std::vector<EnvelopeRow> rows;

 private:
  double budget_s_;
  bool envelope_;
  std::chrono::steady_clock::time_point start_;
};

double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

Scene sceneFromRig(const std::string& name, const Rig& rig) {
  Scene s;
  s.name = name;
  s.rig = rig;
  s.scaled = computeScaled(rig);
  s.periods = rig.sim.t_end_s / (kTwoPi * s.scaled.time_scale_s);
  return s;
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  Scene s = sceneFromRig(std::filesystem::path(path).stem().string(), loadRigFile(path, overrides));
  s.path = path;
  return s;
}

std::string Method::setting() const {
  char buf[64];
  if (engine == "siconos")
    std::snprintf(buf, sizeof buf, "h=T/%g", steps_per_period);
  else
    std::snprintf(buf, sizeof buf, "%.0e", accuracy);
  return buf;
}

bool engineAvailable(const std::string& engine) {
  const Engine* e = findEngine(engine);
  if (e) return e->model() == "full";  // the bench times the full model's engines
  if (engine == "siconos") return siconosAvailable();
  if (engine == "odeint") return odeintAvailable();
  if (engine == "peer") return !peerLocation().path.empty();
  if (engine == "run") return runMethodMissing().empty();
  return false;
}

std::vector<std::string> integratorsOf(const std::string& engine) {
  if (const Engine* e = findEngine(engine)) return e->integrators();
  if (engine == "siconos") return {"moreau-jean"};
  if (engine == "odeint") return odeintIntegratorNames();
  if (engine == "peer") return peerIntegratorNames();
  if (engine == "run") return runIntegratorNames();
  return {};
}

Method parseMethod(const std::string& spec) {
  Method m;
  const size_t a = spec.find(':');
  m.engine = spec.substr(0, a);
  if (m.engine == "peer" && !engineAvailable(m.engine))
    throw std::invalid_argument("'" + spec + "': " + peerLocation().missing);
  if (m.engine == "run" && !engineAvailable(m.engine))
    throw std::invalid_argument("'" + spec + "': " + runMethodMissing());
  if (!engineAvailable(m.engine))
    throw std::invalid_argument(
        "'" + spec + "': engine '" + m.engine + "' is not available (simbody, direct" +
        (siconosAvailable() ? ", siconos" : "; siconos: not built") +
        (odeintAvailable() ? ", odeint" : "; odeint: not built") + ", peer, run)");
  std::string rest = a == std::string::npos ? "" : spec.substr(a + 1);
  const size_t b = rest.find(':');
  m.integrator = rest.substr(0, b);
  if (m.integrator.empty()) m.integrator = integratorsOf(m.engine).front();
  if (!contains(integratorsOf(m.engine), m.integrator))
    throw std::invalid_argument("'" + spec + "': '" + m.integrator + "' is not an integrator of " +
                                m.engine);
  if (b != std::string::npos) {
    const double v = std::stod(rest.substr(b + 1));
    if (!(v > 0)) throw std::invalid_argument("'" + spec + "': the setting must be > 0");
    (m.engine == "siconos" ? m.steps_per_period : m.accuracy) = v;
  }
  return m;
}

RunResult runOnce(const Scene& scene, const Method& method, double budget_s, Sampling sampling) {
  if (method.engine == "peer") return runCarefulPeer(scene, method, 1, budget_s).result;
  if (method.engine == "run") return runMetrosyncCommand(scene, method, 1, budget_s).result;
  RunResult r;
  r.method = method;
  Rig rig = scene.rig;
  rig.sim.integrator = method.engine == "siconos" ? "" : method.integrator;
  if (method.accuracy > 0) rig.sim.accuracy = method.accuracy;

  BenchSink sink(budget_s, sampling);
  RunReport rep;
  const double cpu0 = cpuSeconds();
  const auto wall0 = std::chrono::steady_clock::now();
  try {
    if (const Engine* e = findEngine(method.engine)) {
      rep = e->run(rig, sink);
    } else if (method.engine == "siconos") {
      const std::string why = siconosUnsupported(rig);
      if (!why.empty()) throw std::invalid_argument("siconos peer: " + why);
      SiconosOptions opt;
      opt.step_s = kTwoPi * scene.scaled.time_scale_s / method.steps_per_period;
      rep = runSiconosPeer(rig, sink, opt);
    } else if (method.engine == "odeint") {
      rep = runOdeintPeer(rig, sink, {method.integrator, rig.sim.accuracy});
    } else {
      throw std::invalid_argument("unknown engine " + method.engine);
    }
  } catch (const OverBudget&) {
    r.over_budget = true;
    rep.complete = false;
    rep.failure = "over the time budget";
  } catch (const SimulationFailure& f) {
    rep.complete = false;
    rep.failure = f.why;
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.cpu_s = cpuSeconds() - cpu0;
  r.complete = rep.complete;
  r.failure = rep.failure;
  r.counts = rep.counts;
  for (long e : rep.counts.escapements) r.ticks += e;
  r.envelope = std::move(sink.rows);
  r.final_state = scaledFinalState(scene, rep.final_trajectory_row);
  if (r.complete && sampling == Sampling::FinalState) {
    r.regime = "n/a (final state only)";
  } else if (r.complete) {
    std::vector<bool> locked;
    for (const auto& m : rig.metronomes) locked.push_back(m.locked);
    r.regime = classifyRegime(r.envelope, scene.scaled.tau_end, scene.scaled.epsilon,
                              scene.scaled.theta_c, locked)
                   .name;
  } else {
    r.regime = "unknown";
  }
  return r;
}

ErrorVsRef compareRuns(const RunResult& run, const RunResult& ref) {
  ErrorVsRef e;
  const size_t n = std::min(run.envelope.size(), ref.envelope.size());
  e.rows = static_cast<long>(n);
  for (size_t k = 0; k < n; ++k) {
    const EnvelopeRow& a = run.envelope[k];
    const EnvelopeRow& b = ref.envelope[k];
    for (size_t i = 0; i < a.A.size() && i < b.A.size(); ++i)
      e.max_dA = std::max(e.max_dA, std::abs(a.A[i] - b.A[i]));
    for (size_t j = 0; j < a.psi.size() && j < b.psi.size(); ++j)
      e.max_dpsi = std::max(e.max_dpsi, std::abs(wrapToPi(a.psi[j] - b.psi[j])));
  }
  e.envelope = std::max(e.max_dA, e.max_dpsi);
  if (n == 0)  // a run without an envelope (the careful peer, a final-state run): not measured
    e.max_dA = e.max_dpsi = e.envelope = std::numeric_limits<double>::quiet_NaN();
  if (run.final_state.size() == ref.final_state.size() && !run.final_state.empty()) {
    for (size_t k = 0; k < run.final_state.size(); ++k)
      e.final_state = std::max(e.final_state, std::abs(run.final_state[k] - ref.final_state[k]));
  } else {
    e.final_state = std::numeric_limits<double>::quiet_NaN();
  }
  if (!run.complete || !ref.complete) e.final_state = std::numeric_limits<double>::quiet_NaN();
  return e;
}

double loadAverage1() {
  std::ifstream f("/proc/loadavg");
  double l = std::numeric_limits<double>::quiet_NaN();
  if (f) f >> l;
  return l;
}

#ifndef METROSYNC_HAVE_SICONOS
// Built without Siconos: the peer is absent.
bool siconosAvailable() {
  return false;
}
std::string siconosUnsupported(const Rig&) {
  return "this binary was built without Siconos";
}
RunReport runSiconosPeer(const Rig&, RunSink&, const SiconosOptions&) {
  throw std::invalid_argument("this binary was built without Siconos");
}
#endif

#ifndef METROSYNC_HAVE_ODEINT
// Built without Boost: the peer is absent.
bool odeintAvailable() {
  return false;
}
std::vector<std::string> odeintIntegratorNames() {
  return {};
}
RunReport runOdeintPeer(const Rig&, RunSink&, const OdeintOptions&) {
  throw std::invalid_argument("this binary was built without Boost.Odeint");
}
#endif

}  // namespace metrosync::bench
