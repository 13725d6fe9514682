#include "sim/analysis/validation/validation_runs.h"

#include <chrono>
#include <complex>
#include <exception>

#include "contact/averaged_response.h"
#include "sim/analysis/validation/validation_catalogue.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"

namespace metrosync {

namespace {

// both metronomes ticking (a live synchronized or drifting state)
bool isAliveRegime(Regime r) {
  return r == Regime::InPhase || r == Regime::Antiphase || r == Regime::PhaseLocked ||
         r == Regime::Drift || r == Regime::Unsettled;
}

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Keeps what validation needs from a run: every envelope row (one per fast period: O(tau/eps)
// rows, small) and, from the trajectory rows, how often the platform was stuck in the regime
// window. Trajectory rows are counted, not kept.
class KeepingSink : public RunSink {
 public:
  KeepingSink(double epsilon, double tau_window_start)
      : epsilon_(epsilon), tau_window_start_(tau_window_start) {}
  void envelopeRow(const EnvelopeRow& row) override { rows.push_back(row); }
  void trajectoryRow(const std::vector<double>& row) override {
    // validation rigs are scaled: row[0] is scaled time t, tau = epsilon t
    if (epsilon_ * row[0] < tau_window_start_) return;
    ++window_rows;
    if (row.back() == 0.0) ++stuck_rows;
  }
  std::vector<EnvelopeRow> rows;
  long window_rows = 0, stuck_rows = 0;

 private:
  double epsilon_, tau_window_start_;
};

double windowStart(double tau_end, double epsilon) {
  return RegimeWindow(tau_end, epsilon).tauStart();  // the regime's window (sim/analysis/regime.h)
}

// A run of `model` of p at epsilon to tau_end, before it ran.
ModelRun modelRun(const char* model, const ScaledParams& p, double epsilon, double tau_end) {
  ModelRun run;
  run.model = model;
  run.epsilon = epsilon;
  run.tau_end = tau_end;
  run.mu = p.friction.valueOr("mu", 0.0);
  run.theta_c = p.theta_c;
  return run;
}

}  // namespace

std::string sweepLabel(const ModelRun& run) {
  if (!run.report.complete) return "failed";
  const Regime g = run.verdict.regime;
  std::string label = toString(g);
  if (isAliveRegime(g) && run.platform == "stuck") label += ", uncoupled";
  return label;
}

ModelRun runSlowModel(const ScaledParams& p, double epsilon, double tau_end) {
  ModelRun run = modelRun("slow", p, epsilon, tau_end);
  ScaledParams q = p;
  q.epsilon = epsilon;
  q.tau_end = tau_end;
  KeepingSink sink(epsilon, windowStart(tau_end, epsilon));
  SlowFlowOptions opt;
  opt.tau_end = tau_end;
  run.report = runSlowFlow(q, opt, sink);
  run.envelope = std::move(sink.rows);
  if (run.report.complete)
    run.verdict = classifyRegime(run.envelope, tau_end, epsilon, q.theta_c, q.locked);
  // the platform at the end: the Coulomb regime of the final drive s = |Z| / mu (a dry law)
  const EnvelopeRow& f = run.report.final_row;
  if (p.friction.slowResponse().hasBorders() && !f.A.empty()) {
    std::complex<double> Z = f.A[0];
    for (size_t j = 1; j < f.A.size(); ++j) Z += std::polar(f.A[j], -f.psi[j - 1]);
    const double mu = run.mu;
    const double s = mu > 0 ? std::abs(Z) / mu : std::numeric_limits<double>::infinity();
    run.platform = toString(coulombRegime(s));
  }
  return run;
}

ModelRun runFullModelAt(const ValidationEngines& engines, const ScaledParams& p,
                        const std::string& name, double epsilon, double tau_end) {
  ModelRun run = modelRun("full", p, epsilon, tau_end);
  const Rig rig = rigAtEpsilon(p, name, epsilon, tau_end);
  KeepingSink sink(epsilon, windowStart(tau_end, epsilon));
  const Clock::time_point t0 = Clock::now();
  try {
    run.report = engines.full_model(rig, sink);
  } catch (const SimulationFailure& f) {
    run.report.complete = false;
    run.report.failure = f.why;
  } catch (const std::exception& e) {
    run.report.complete = false;
    run.report.failure = e.what();
  }
  if (run.report.wall_seconds == 0.0) run.report.wall_seconds = secondsSince(t0);
  run.envelope = std::move(sink.rows);
  if (run.report.final_row.A.empty() && !run.envelope.empty())
    run.report.final_row = run.envelope.back();
  if (run.report.complete)
    run.verdict = classifyRegime(run.envelope, tau_end, epsilon, p.theta_c, p.locked);
  if (p.friction.setValued() && sink.window_rows > 0) {
    run.platform_stuck_fraction =
        static_cast<double>(sink.stuck_rows) / static_cast<double>(sink.window_rows);
    // the share of the window the platform spends at rest: "stuck" and "slipping" allow 1% for
    // the sampling of a switch that happens at the window's edges
    run.platform = run.platform_stuck_fraction > 0.99   ? "stuck"
                   : run.platform_stuck_fraction < 0.01 ? "slipping"
                                                        : "stick-slip";
  }
  return run;
}

}  // namespace metrosync
