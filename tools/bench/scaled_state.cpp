#include "tools/bench/scaled_state.h"

namespace metrosync::bench {

std::vector<double> scaledFinalState(const Scene& scene, const std::vector<double>& row) {
  const int n = static_cast<int>(scene.rig.metronomes.size());
  if (static_cast<int>(row.size()) < 3 + 2 * n) return {};
  const ScaledParams& sp = scene.scaled;
  const bool physical = scene.rig.units == Units::Physical;
  const double omega0 = 1.0 / sp.time_scale_s;
  const double vx = physical ? 1.0 / (sp.x_scale_m * omega0) : 1.0;
  const double th = physical ? 1.0 / sp.angle_scale : 1.0;
  const double w = physical ? 1.0 / (sp.angle_scale * omega0) : 1.0;
  std::vector<double> s = {row[2] * vx};
  for (int i = 0; i < n; ++i) {
    s.push_back(row[3 + 2 * i] * th);
    s.push_back(row[4 + 2 * i] * w);
  }
  return s;
}

}  // namespace metrosync::bench
