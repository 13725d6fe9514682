// The branches through each locked state `continue --all` starts from, computed on demand from
// any thread: a state's own (followed by the arclength continuation), or, for a copy of an
// earlier state with identical metronomes exchanged (exchanges.h), its original's mapped through
// the exchange. Each original is followed once, by the first thread that needs it.
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "sim/analysis/continuation/slow_flow_continuation.h"
#include "sim/analysis/continuation/slow_flow_problem.h"

namespace metrosync::continuation {

// The branches through a locked state, in the problem they were followed in.
struct Traced {
  std::shared_ptr<const SlowFlowProblem> prob;
  std::vector<Branch> branches;
};

// A problem at spec.from with the state's largest amplitude as its reference (z_r real stays
// regular while z_r does not vanish).
std::shared_ptr<const SlowFlowProblem> problemFor(const SlowFlowContinuationSpec& spec,
                                                  const std::vector<std::complex<double>>& z);

// The branches through x, a locked state of prob at spec.from.
Traced traceState(const std::shared_ptr<const SlowFlowProblem>& prob, const Vec& x,
                  const SlowFlowContinuationSpec& spec);

class StateTraces {
 public:
  // states: locked states of grid at spec.from. Finds which are copies of earlier ones.
  StateTraces(const SlowFlowContinuationSpec& spec, const SlowFlowProblem& grid,
              const std::vector<Vec>& states);
  // The branches through state k (a copy's mapped from its original's); rethrows what following
  // the original threw. Safe from several threads at once.
  Traced of(long k);
  // The earlier state k is a copy of (its branches mapped from that state's), -1 for none.
  long originalOf(long k) const { return original_[static_cast<size_t>(k)]; }

 private:
  struct Once {
    std::once_flag flag;
    Traced value;
    std::exception_ptr error;
  };
  const Traced& own(long k);

  const SlowFlowContinuationSpec& spec_;
  const SlowFlowProblem& grid_;
  const std::vector<Vec>& states_;
  std::vector<long> original_;           // -1: its own original
  std::vector<std::vector<int>> sigma_;  // a copy's exchange: z_i = z_original,sigma(i)
  std::vector<std::unique_ptr<Once>> own_;
};

}  // namespace metrosync::continuation
