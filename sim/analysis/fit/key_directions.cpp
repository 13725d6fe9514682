#include "sim/analysis/fit/key_directions.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace metrosync {

namespace {

// The model's parameters with key j at v, or nothing where no rig exists there.
std::optional<orbit::Vec> parametersAt(const FitProblem& p, std::vector<double> values,
                                       std::size_t j, double v, const orbit::PhysicalModel& model) {
  values[j] = v;
  Rig rig;
  try {
    rig = p.rig(values);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const orbit::PhysicalModel moved(rig);
  const orbit::ParameterLayout &a = moved.parameterLayout(), &b = model.parameterLayout();
  if (a.n != b.n || a.law_values != b.law_values || !moved.law().is(model.law().kind()))
    throw std::invalid_argument("--free " + p.free[j].name +
                                ": the key changes the model's shape, not only its constants");
  return moved.parameters();
}

}  // namespace

orbit::Mat keyDirections(const FitProblem& p, const std::vector<double>& values,
                         const std::vector<bool>& wanted, const orbit::PhysicalModel& model) {
  const orbit::Vec p0 = model.parameters();
  orbit::Mat dirs = orbit::Mat::Zero(p0.size(), static_cast<int>(values.size()));
  for (std::size_t j = 0; j < values.size(); ++j) {
    if (!wanted[j]) continue;
    const double h = kKeyStep * std::max(std::abs(values[j]), p.free[j].scale);
    const std::optional<orbit::Vec> hi = parametersAt(p, values, j, values[j] + h, model);
    const std::optional<orbit::Vec> lo = parametersAt(p, values, j, values[j] - h, model);
    if (hi && lo)
      dirs.col(j) = (*hi - *lo) / (2 * h);
    else if (hi || lo)  // at a bound: one-sided
      dirs.col(j) = hi ? orbit::Vec((*hi - p0) / h) : orbit::Vec((p0 - *lo) / h);
    else
      throw std::invalid_argument("--free " + p.free[j].name + ": no rig on either side of " +
                                  std::to_string(values[j]));
  }
  return dirs;
}

}  // namespace metrosync
