#include "sim/analysis/validation/validation_experiments.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "base/constants.h"
#include "base/number_text.h"
#include "models/scaling.h"
#include "sim/parallel/worker_pool.h"

namespace metrosync {

namespace {

constexpr double kNever = std::numeric_limits<double>::quiet_NaN();

// Upward zero crossings of the first pendulum's angle (trajectory rows: t, x, xdot, theta_1, ...)
// from t_from on, each placed by linear interpolation between its two rows.
class CrossingSink : public RunSink {
 public:
  explicit CrossingSink(double t_from) : t_from_(t_from) {}
  bool wantsEnvelope() const override { return false; }
  bool wantsEventRows() const override { return false; }
  void trajectoryRow(const std::vector<double>& row) override {
    const double t = row[0], th = row[3];
    if (have_ && t_prev_ > t_from_ && th_prev_ < 0 && th >= 0)
      up.push_back(t_prev_ - th_prev_ * (t - t_prev_) / (th - th_prev_));
    t_prev_ = t;
    th_prev_ = th;
    have_ = true;
  }
  std::vector<double> up;

 private:
  double t_from_, t_prev_ = 0.0, th_prev_ = 0.0;
  bool have_ = false;
};

// The scenario's file (the experiment's rigs are shipped scenarios).
const std::string& scenarioFile(const std::vector<Scenario>& scenarios, const std::string& name) {
  return findScenario(scenarios, name).spec.file;
}

std::string inertiaSet(double inertia) {
  return "metronomes.*.pendulum.inertia=" + numberText(inertia, 17);
}

}  // namespace

const std::vector<ExperimentSpec>& paperExperiments() {
  static const std::vector<ExperimentSpec> kExperiments = {
      {"experiment-low-friction-antiphase", "fig. exp2 (fig. exp1, left, low friction)",
       "started near antiphase on the large rollers: leaves pi after about 10 s, ends in phase",
       Regime::InPhase, ExperimentClock::LeavesAntiphase, 10.0},
      {"experiment-high-friction-inphase", "fig. exp3 (fig. exp1, right, high friction)",
       "started in phase on the small rollers on styrofoam: oscillator death after a little over "
       "20 s",
       Regime::Death, ExperimentClock::Dies, 20.0},
      {"experiment-high-friction-antiphase", "fig. exp1, left, high friction",
       "started near antiphase, high friction: stays in antiphase", Regime::Antiphase,
       ExperimentClock::None, 0.0},
      {"experiment-low-friction-inphase", "fig. exp1, right, low friction",
       "started in phase, low friction: stays in phase", Regime::InPhase, ExperimentClock::None,
       0.0},
  };
  return kExperiments;
}

double oneMetronomeFrequency(const ValidationEngines& engines, const std::string& rig_file,
                             std::vector<std::string> sets) {
  constexpr double kFrom = 5.0, kDuration = 20.0;  // s: past the start's transient
  sets.insert(sets.begin(),
              {"platform.friction={law: fixed}", "metronomes.1.locked=true",
               "simulation.duration=" + numberText(kDuration), "simulation.sample=0.0005"});
  const Rig rig = engines.load_rig(rig_file, sets);
  CrossingSink sink(kFrom);
  const RunReport rep = engines.full_model(rig, sink);
  if (!rep.complete) throw std::runtime_error("one metronome of " + rig_file + ": " + rep.failure);
  if (sink.up.size() < 2)
    throw std::runtime_error("one metronome of " + rig_file + ": it does not swing");
  return static_cast<double>(sink.up.size() - 1) / (sink.up.back() - sink.up.front());
}

InertiaSearch inertiaForFrequency(const ValidationEngines& engines, const std::string& rig_file,
                                  const std::vector<std::string>& sets, double start_inertia,
                                  double hz) {
  InertiaSearch search;
  auto frequencyAt = [&](double inertia) {
    std::vector<std::string> with = sets;
    with.push_back(inertiaSet(inertia));
    ++search.runs;
    return oneMetronomeFrequency(engines, rig_file, with);
  };
  search.inertia = start_inertia;
  search.start_hz = search.hz = frequencyAt(start_inertia);
  for (int k = 0; k < kInertiaIterations && std::abs(search.hz - hz) > 1e-4 * hz; ++k) {
    search.inertia *= (search.hz / hz) * (search.hz / hz);  // f ~ I^(-1/2) at a fixed amplitude
    search.hz = frequencyAt(search.inertia);
  }
  return search;
}

double experimentClock(const ExperimentSpec& e, const ModelRun& run) {
  const std::vector<EnvelopeRow>& rows = run.envelope;
  if (rows.empty() || !(run.epsilon > 0)) return kNever;
  auto seconds = [&](double tau) { return tau / run.epsilon * run.time_scale_s; };
  if (e.clock == ExperimentClock::LeavesAntiphase) {
    for (const EnvelopeRow& r : rows)
      if (!r.psi.empty() && std::abs(std::remainder(r.psi[0] - kPi, 2 * kPi)) > kLeavesAntiphaseRad)
        return seconds(r.tau);
    return kNever;
  }
  if (e.clock == ExperimentClock::Dies) {
    auto ticking = [&](const EnvelopeRow& r) {
      for (size_t i = 0; i < r.A.size() && i < run.theta_c.size(); ++i)
        if (r.A[i] >= run.theta_c[i]) return true;
      return false;
    };
    if (ticking(rows.back())) return kNever;  // still ticking at the end
    size_t k = rows.size();
    while (k > 0 && !ticking(rows[k - 1])) --k;
    return seconds(rows[k < rows.size() ? k : rows.size() - 1].tau);
  }
  return kNever;
}

ExperimentOutcome judgeExperiment(const ExperimentSpec& e, const std::string& variant,
                                  ModelRun run) {
  ExperimentOutcome o;
  o.scenario = e.scenario;
  o.variant = variant;
  o.clock_s = experimentClock(e, run);
  o.regime_ok = run.report.complete && run.verdict.regime == e.regime;
  o.clock_ok =
      e.clock == ExperimentClock::None ||
      (std::isfinite(o.clock_s) && o.clock_s >= e.seconds / 2 && o.clock_s <= 2 * e.seconds);
  o.run = std::move(run);
  return o;
}

ExperimentsResult runExperiments(double frequency_hz, const std::vector<Scenario>& scenarios,
                                 const ValidationEngines& engines, ValidationLog& log, int jobs) {
  ExperimentsResult res;
  res.frequency_hz = frequency_hz;
  const std::string& base = scenarioFile(scenarios, paperExperiments().front().scenario);
  res.shipped_inertia = engines.load_rig(base, {}).metronomes.front().inertia_kgm2;
  // the search starts at the shipped inertia: its first run is the shipped metronome's
  const InertiaSearch search =
      inertiaForFrequency(engines, base, {}, res.shipped_inertia, frequency_hz);
  res.shipped_hz = search.start_hz;
  res.inertia = search.inertia;
  res.variant_hz = search.hz;
  log.say("experiments: one metronome ticks at " + numberText(res.shipped_hz, 5) +
          " Hz as shipped, at " + numberText(res.variant_hz, 5) + " Hz with I = " +
          numberText(res.inertia, 4) + " kg m^2 (" + std::to_string(search.runs) + " runs)");
  res.variants = {
      {"as shipped", "I = m L^2 (the paper's assumption, section 3B)", {}},
      {"measured frequency",
       "I = " + numberText(res.inertia, 4) + " kg m^2, " +
           numberText(res.inertia / res.shipped_inertia, 3) + " m L^2: alone it ticks at " +
           numberText(frequency_hz) + " Hz (section 3D)",
       {inertiaSet(res.inertia)}},
  };
  const auto& exps = paperExperiments();
  const size_t nv = res.variants.size();
  res.outcomes.resize(exps.size() * nv);
  parallelFor(static_cast<long>(res.outcomes.size()), jobs, [&](long k) {
    const ExperimentSpec& e = exps[k / nv];
    const ExperimentVariant& v = res.variants[k % nv];
    const ScaledParams p =
        computeScaled(engines.load_rig(scenarioFile(scenarios, e.scenario), v.sets));
    ModelRun run = runFullModelAt(engines, p, e.scenario, p.epsilon, p.tau_end);
    run.time_scale_s = p.time_scale_s;
    res.outcomes[k] = judgeExperiment(e, v.name, std::move(run));
    log.run("experiment " + e.scenario + " (" + v.name + ")", res.outcomes[k].run);
  });
  return res;
}

}  // namespace metrosync
