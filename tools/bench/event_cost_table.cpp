#include "tools/bench/event_cost_table.h"

#include <sstream>

#include "tools/bench/bench_metrics.h"

namespace metrosync::bench {

namespace {

// "33.2 us", "1.09 ms"
std::string micro(double s) {
  return s < 1e-3 ? benchNumber(1e6 * s, 3) + " us" : benchNumber(1e3 * s, 3) + " ms";
}

}  // namespace

std::string eventCostCsv(const std::vector<EventCostRow>& rows, double load_min, double load_max) {
  std::string s =
      "scene,n,integrator,accuracy,runs,steps,rhs_evals,events,cpu_s,rhs_s,evals_per_step,"
      "evals_per_event,s_per_step,s_per_event,step_in_rhs,event_in_rhs,rhs_share,load1_min,"
      "load1_max,failure\n";
  for (const EventCostRow& r : rows) {
    s += csvField(r.scene) + "," + std::to_string(r.n) + "," + r.integrator + "," +
         benchNumber(r.accuracy, 3) + "," + std::to_string(r.runs) + ",";
    if (r.failure.empty())
      s += std::to_string(r.steps) + "," + std::to_string(r.rhs_evals) + "," +
           std::to_string(r.events) + "," + benchNumber(r.cpu_s, 6) + "," +
           benchNumber(r.rhs_s, 6) + "," + benchNumber(r.evalsPerStep(), 6) + "," +
           benchNumber(r.evalsPerEvent(), 6) + "," + benchNumber(r.secondsPerStep(), 6) + "," +
           benchNumber(r.secondsPerEvent(), 6) + "," + benchNumber(r.stepInRhs(), 6) + "," +
           benchNumber(r.eventInRhs(), 6) + "," + benchNumber(r.rhsShare(), 6) + ",";
    else
      s += ",,,,,,,,,,,,";
    s += benchNumber(load_min, 2, Notation::Fixed) + "," +
         benchNumber(load_max, 2, Notation::Fixed) + "," + csvField(r.failure) + "\n";
  }
  return s;
}

std::string eventCostMarkdown(const std::vector<EventCostRow>& rows, const std::string& command) {
  std::ostringstream os;
  os << "The direct engine without samples (the bench's final-state runs, CPU medians) at each "
        "N: its whole cost divided by its steps and by its events, in RHS evaluations and in "
        "time, and each against one RHS evaluation timed alone (the same equations, N known to "
        "the compiler as in the run, a slipping platform; CPU median over batches). \"x RHS\": "
        "that time in units of one evaluation; RHS share: evaluations x their time / the run's "
        "time.\n\n"
     << "| scene | N | integrator | accuracy | steps | events | RHS evals | evals / step | "
        "evals / event | one RHS | time / step | x RHS | time / event | x RHS | RHS share |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const EventCostRow& r : rows) {
    os << "| " << r.scene << " | " << r.n << " | " << r.integrator << " | "
       << benchNumber(r.accuracy, 0, Notation::Scientific) << " | ";
    if (!r.failure.empty()) {
      os << "failed: " << r.failure << " |  |  |  |  |  |  |  |  |  |  |\n";
      continue;
    }
    os << r.steps << " | " << r.events << " | " << r.rhs_evals << " | "
       << benchNumber(r.evalsPerStep(), 3) << " | " << benchNumber(r.evalsPerEvent(), 3) << " | "
       << micro(r.rhs_s) << " | " << micro(r.secondsPerStep()) << " | "
       << benchNumber(r.stepInRhs(), 3) << " | " << micro(r.secondsPerEvent()) << " | "
       << benchNumber(r.eventInRhs(), 3) << " | " << benchNumber(100 * r.rhsShare(), 2) << "% |\n";
  }
  if (!command.empty()) os << "\nMade by:\n\n    " << command << "\n";
  return os.str();
}

}  // namespace metrosync::bench
