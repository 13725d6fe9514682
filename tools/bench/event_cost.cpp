#include "tools/bench/event_cost.h"

#include <time.h>

#include <cmath>
#include <iostream>

#include "base/number_text.h"
#include "base/thread_cpu_time.h"
#include "models/network_equations.h"
#include "sim/engines/direct/direct_integrators.h"
#include "sim/engines/direct/start_state.h"

namespace metrosync::bench {

namespace {

using network::NetworkEquations;

// Batches of evaluations, each about this long: far above the clock's resolution.
constexpr double kBatchS = 2e-3;
constexpr int kBatches = 15;

// `count` evaluations at y (each result fed back into y by a vanishing amount, so that none can
// be skipped); their CPU seconds.
template <int N>
double timeEvaluations(const NetworkEquations& eq, std::vector<double>& y, long count) {
  std::vector<double> dy(y.size());
  const double t0 = threadCpuSeconds();
  for (long k = 0; k < count; ++k) {
    eq.rhsN<N>(y.data(), PlatformMode::SlipPositive, dy.data());
    y[1] += 1e-300 * dy[1];
  }
  return threadCpuSeconds() - t0;
}

template <int N>
double medianEvaluation(const NetworkEquations& eq, std::vector<double>& y) {
  long count = 16;
  while (timeEvaluations<N>(eq, y, count) < kBatchS && count < (1L << 30)) count *= 2;
  std::vector<double> per;
  for (int b = 0; b < kBatches; ++b)
    per.push_back(timeEvaluations<N>(eq, y, count) / static_cast<double>(count));
  return median(per);
}

// The rig's default integrator's name, or the one it names.
std::string integratorOf(const Rig& rig) {
  return rig.sim.integrator.empty() ? defaultDirectIntegrator(rig) : rig.sim.integrator;
}

EventCostRow measureOne(const Scene& scene, double accuracy, double rhs_s, const BenchOptions& c) {
  EventCostRow row;
  row.scene = scene.name;
  row.n = static_cast<int>(scene.rig.metronomes.size());
  row.integrator = integratorOf(scene.rig);
  row.accuracy = accuracy;
  row.rhs_s = rhs_s;
  const Method m{"direct", row.integrator, accuracy};
  std::vector<double> cpus;
  for (int k = 0; k < c.repeat; ++k) {
    waitForLoad(c);
    const RunResult r = runOnce(scene, m, c.budget_s, Sampling::FinalState);
    if (!r.complete) {
      row.failure = r.failure;
      return row;
    }
    if (k == 0)
      row.steps = r.counts.steps, row.rhs_evals = r.counts.rhs_evals, row.events = r.counts.events;
    cpus.push_back(r.cpu_s);
  }
  row.cpu_s = median(cpus);
  row.runs = static_cast<int>(cpus.size());
  return row;
}

}  // namespace

double rhsSeconds(const Rig& rig) {
  const NetworkEquations eq(rig);
  std::vector<double> y(eq.layout().dim(), 0.0);
  direct::writePlatformStart(rig, eq.hasPlatform(), eq.layout(), 0, 0, y.data());
  switch (eq.numSwinging()) {  // as runDirectModel dispatches
    case 1:
      return medianEvaluation<1>(eq, y);
    case 2:
      return medianEvaluation<2>(eq, y);
    case 3:
      return medianEvaluation<3>(eq, y);
    case 4:
      return medianEvaluation<4>(eq, y);
    case 5:
      return medianEvaluation<5>(eq, y);
    case 6:
      return medianEvaluation<6>(eq, y);
    case 7:
      return medianEvaluation<7>(eq, y);
    case 8:
      return medianEvaluation<8>(eq, y);
    default:
      return medianEvaluation<NetworkEquations::kAnyN>(eq, y);
  }
}

std::vector<EventCostRow> measureEventCost(const EventCostOptions& o, const BenchOptions& c) {
  std::vector<EventCostRow> rows;
  for (const std::string& path : o.scenes) {
    const Scene scene = loadScene(path);
    waitForLoad(c);
    const double rhs_s = rhsSeconds(scene.rig);
    for (double a : o.accuracies) {
      rows.push_back(measureOne(scene, a, rhs_s, c));
      const EventCostRow& r = rows.back();
      if (!c.quiet)
        std::cerr << "  " << r.scene << " (N = " << r.n << ") " << r.integrator << " "
                  << numberText(a, 1, Notation::Scientific) << ": "
                  << (r.failure.empty() ? numberText(r.evalsPerStep(), 3) + " evals / step, " +
                                              numberText(r.stepInRhs(), 3) + " RHS / step, " +
                                              numberText(r.eventInRhs(), 3) + " RHS / event"
                                        : "failed: " + r.failure)
                  << "\n";
    }
  }
  return rows;
}

}  // namespace metrosync::bench
