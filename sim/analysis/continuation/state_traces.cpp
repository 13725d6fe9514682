#include "sim/analysis/continuation/state_traces.h"

#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/exchanges.h"

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// A state is a copy of another when the exchange matches every z_i to this (the states are
// Newton solutions to 1e-12; distinct states differ by O(0.1), and alreadyFollowed calls a state
// on a branch at 1e-3).
constexpr double kSameCopy = 1e-7;

}  // namespace

std::shared_ptr<const SlowFlowProblem> problemFor(const SlowFlowContinuationSpec& spec,
                                                  const std::vector<Cd>& z) {
  int r = 0;
  for (size_t i = 1; i < z.size(); ++i)
    if (std::abs(z[i]) > std::abs(z[r])) r = static_cast<int>(i);
  return std::make_shared<const SlowFlowProblem>(spec.params, spec.from, r);
}

Traced traceState(const std::shared_ptr<const SlowFlowProblem>& prob, const Vec& x,
                  const SlowFlowContinuationSpec& spec) {
  return {prob, continueFrom(prob->system(), x, spec.from, spec.settings)};
}

StateTraces::StateTraces(const SlowFlowContinuationSpec& spec, const SlowFlowProblem& grid,
                         const std::vector<Vec>& states)
    : spec_(spec),
      grid_(grid),
      states_(states),
      original_(states.size(), -1),
      sigma_(states.size()) {
  const std::vector<int> classes = exchangeClasses(spec.params, spec.from, spec.to);
  for (size_t k = 0; k < states.size(); ++k) {
    own_.push_back(std::make_unique<Once>());
    const std::vector<Cd> z = grid.unpack(states[k]);
    for (size_t j = 0; j < k && original_[k] < 0; ++j) {
      if (original_[j] >= 0) continue;  // a copy's copy is its original's
      if (auto sigma = exchangeOf(z, grid.unpack(states[j]), classes, kSameCopy))
        original_[k] = static_cast<long>(j), sigma_[k] = std::move(*sigma);
    }
  }
}

const Traced& StateTraces::own(long k) {
  Once& once = *own_[static_cast<size_t>(k)];
  std::call_once(once.flag, [&] {
    try {
      const std::vector<Cd> z = grid_.unpack(states_[static_cast<size_t>(k)]);
      const auto prob = problemFor(spec_, z);
      once.value =
          traceState(prob, prob->pack(z, grid_.omega(states_[static_cast<size_t>(k)])), spec_);
    } catch (...) {
      once.error = std::current_exception();
    }
  });
  if (once.error) std::rethrow_exception(once.error);
  return once.value;
}

Traced StateTraces::of(long k) {
  const long o = original_[static_cast<size_t>(k)];
  if (o < 0) return own(k);
  const Traced& t = own(o);
  const std::vector<int>& sigma = sigma_[static_cast<size_t>(k)];
  const auto prob = std::make_shared<const SlowFlowProblem>(
      spec_.params, spec_.from, exchangedReference(sigma, t.prob->reference()));
  return {prob, exchangedBranches(*t.prob, *prob, sigma, t.branches)};
}

}  // namespace metrosync::continuation
