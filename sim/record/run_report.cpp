#include "sim/record/run_report.h"

#include <algorithm>
#include <cmath>

namespace metrosync {

double EnergyLedger::relativeResidual() const {
  const double scale = std::max({std::abs(initial_J), std::abs(final_J), escapement_in_J,
                                 damping_out_J, friction_out_J, 1e-300});
  return residual_J() / scale;
}

}  // namespace metrosync
