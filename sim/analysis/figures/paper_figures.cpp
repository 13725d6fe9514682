#include "sim/analysis/figures/paper_figures.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <stdexcept>

#include "sim/parallel/worker_pool.h"

namespace metrosync {

namespace {

// the paper's curve colours in f4.3 and f4.4: black, red, blue
constexpr const char* kBlack = "#000000";
constexpr const char* kRed = "#d62728";
constexpr const char* kBlue = "#1f4fd6";

const Scenario& scenarioNamed(const std::vector<Scenario>& all, const std::string& name) {
  for (const auto& s : all)
    if (s.spec.name == name) return s;
  throw std::invalid_argument("figures: no scenario named '" + name + "'");
}

}  // namespace

const std::vector<FigureSpec>& paperFigureSpecs() {
  static const std::vector<FigureSpec> specs = {
      {"f4.1",
       "f4.1: identical metronomes, low friction, started near antiphase",
       "Identical metronomes with low platform friction, started close to antiphase (the "
       "simulation of the experiment of figure exp2). nu = 0.5, mu = 0, J = 3.6, theta_c = 0.9, "
       "alpha = 0; A_1(0) = A_2(0) = 1.9, psi(0) = pi + 0.05. The system leaves antiphase and "
       "approaches in-phase synchronization (psi -> 2 pi) through slowly damped oscillations.",
       "the paper's caption says \"the experimental results shown in Fig. f4.1\": the experiment "
       "is figure exp2",
       {{"f4.1", "μ = 0", kBlack}}},
      {"f4.2",
       "f4.2: neutral stability of antiphase, the platform held by friction",
       "Neutral stability of the antiphase state where Coulomb friction keeps the platform at "
       "rest. nu = 0.7, mu = 0.2, J = 2.8, theta_c = 0.9, alpha = 0; A_1(0) = A_2(0) = 1.9, "
       "psi(0) = pi + 0.4. The amplitudes settle, and so does psi, but never at pi (the dashed "
       "line): one of a continuous family of neutrally stable nearly-antiphase states.",
       "",
       {{"f4.2", "μ = 0.2", kBlack}}},
      {"f4.3",
       "f4.3: started near in-phase, three frictions",
       "Identical metronomes started near in-phase for three platform frictions. Black, mu = 0.2: "
       "stays in phase. Red, mu = 0.3: only one amplitude stays above theta_c (dashed), "
       "metronome suppression. Blue, mu = 0.4: both amplitudes decay, oscillator death. "
       "nu = 0.7, J = 2.8, theta_c = 0.9, alpha = 0; A_1(0) = A_2(0) = 1.9, psi(0) = 0.03.",
       "",
       {{"f4.3-mu0.2", "μ = 0.2", kBlack},
        {"f4.3-mu0.3", "μ = 0.3", kRed},
        {"f4.3-mu0.4", "μ = 0.4", kBlue}}},
      {"f4.4",
       "f4.4: non-identical metronomes, three detunings",
       "Non-identical metronomes: detuning alpha on metronome 2 (alpha > 0 makes metronome 2 the "
       "faster one). Black, alpha = 0.2: locked near antiphase, the faster metronome (2) at the "
       "lower amplitude. Red, alpha = 2: the slower metronome (1) suppresses the faster one, "
       "A_2 falls below theta_c (dashed). Blue, alpha = 4: metronome 1 suppresses metronome 2 "
       "for a long time with psi nearly constant, then A_1 falls below theta_c and both die. "
       "nu = 0.7, mu = 0.4, J = 2.8, theta_c = 0.9; A_1(0) = A_2(0) = 1.9, psi(0) = pi + 0.4.",
       "the paper's caption says \"the faster metronome suppresses the slower one\" for alpha = "
       "2; its text, its own \"A_2 falls below\" and the runs say the slower metronome (1) "
       "suppresses the faster (2)",
       {{"f4.4-alpha0.2", "α = 0.2", kBlack},
        {"f4.4-alpha2", "α = 2", kRed},
        {"f4.4-alpha4", "α = 4", kBlue}}},
  };
  return specs;
}

const FigureSpec* findFigureSpec(const std::string& id) {
  for (const auto& f : paperFigureSpecs())
    if (f.id == id) return &f;
  return nullptr;
}

std::vector<std::string> RegimeMapSpec::vary() const {
  // psi0 over [0, 2 pi), and mu from 0: the map's cells are the grid points
  return {mu_key + "=0:" + std::to_string(mu_max) + ":" + std::to_string(mu_count),
          psi0_key + "=0:2pi:" + std::to_string(psi0_count) + ":open"};
}

RegimeMapSpec regimeMapSpec(bool quick) {
  RegimeMapSpec m;
  if (quick) m.mu_count = m.psi0_count = 12;
  m.title = "exp1: computed regime diagram, the experiment's metronomes";
  m.caption =
      "The paper's schematic regime diagram (figure exp1) computed: the long-term state of two "
      "identical metronomes at the experiment's parameters (yaml/rigs/experiment-map.yaml: "
      "epsilon = 0.0732, nu = 0.654, J = 3.138, theta_c = 0.902, both started at A_star = 2.902, "
      "tau = 305.6) against the platform friction mu (across) and the initial phase difference "
      "psi0 (up). Exp1's two panels are the rows psi0 = pi (left panel: antiphase start) and "
      "psi0 = 0 (right panel: in-phase start), dashed; the experiment's two platforms (mu = "
      "0.033 and 0.233) are the dotted verticals.";
  return m;
}

namespace {

// One run: a curve of a figure in one model.
struct RunTask {
  FigureRun* run;
  const Scenario* scenario;
  bool full;
  double cost;
};

void runTask(const RunTask& t, const ValidationEngines& engines) {
  const ScaledParams& p = t.scenario->scaled;
  if (t.full)
    t.run->full = runFullModelAt(engines, p, t.scenario->spec.name, p.epsilon, p.tau_end);
  else
    t.run->slow = runSlowModel(p, p.epsilon, p.tau_end);
}

}  // namespace

std::vector<FigureResult> runPaperFigures(const std::vector<FigureSpec>& figures,
                                          const std::vector<Scenario>& scenarios,
                                          const ValidationEngines& engines, FigureModels models,
                                          int jobs,
                                          const std::function<void(const std::string&)>& progress) {
  std::vector<FigureResult> results;
  results.reserve(figures.size());
  std::vector<RunTask> tasks;
  for (const auto& spec : figures) {
    results.push_back({spec, {}});
    results.back().runs.resize(spec.curves.size());
  }
  for (auto& r : results)
    for (size_t k = 0; k < r.spec.curves.size(); ++k) {
      FigureRun& run = r.runs[k];
      const Scenario& sc = scenarioNamed(scenarios, r.spec.curves[k].scenario);
      run.curve = r.spec.curves[k];
      run.scaled = sc.scaled;
      run.has_slow = models.slow;
      run.has_full = models.full;
      // the full model costs ~ tau / epsilon; the slow flow next to nothing
      if (models.full) tasks.push_back({&run, &sc, true, sc.scaled.tau_end / sc.scaled.epsilon});
      if (models.slow) tasks.push_back({&run, &sc, false, 0.0});
    }
  std::stable_sort(tasks.begin(), tasks.end(),
                   [](const RunTask& a, const RunTask& b) { return a.cost > b.cost; });
  std::mutex lock;  // guards progress
  // the pool (sim/parallel/worker_pool.h): the costliest first, each thread taking the next task
  parallelFor(static_cast<long>(tasks.size()), jobs, [&](long k) {
    runTask(tasks[k], engines);
    const ModelRun& m = tasks[k].full ? tasks[k].run->full : tasks[k].run->slow;
    std::lock_guard<std::mutex> g(lock);
    if (progress)
      progress(tasks[k].scenario->spec.name + " " + (tasks[k].full ? "full" : "slow") + ": " +
               (m.report.complete ? toString(m.verdict.regime) : "FAILED"));
  });
  return results;
}

}  // namespace metrosync
