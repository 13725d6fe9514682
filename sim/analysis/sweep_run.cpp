#include "sim/analysis/sweep_run.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <optional>
#include <string>

namespace metrosync {

std::vector<SweepPoint> runSweep(const SweepGrid& grid,
                                 const std::function<PointInput(long)>& make_point, int jobs,
                                 const std::function<void(const SweepPoint&)>& on_point,
                                 const PointHooks& hooks) {
  std::vector<SweepPoint> rows;
  int n = -1;  // the metronomes of the first point built (a failed point's row size)
  std::mutex first;
  auto run = [&](long g) -> std::optional<SweepPoint> {
    std::optional<PointInput> in;
    try {
      in = make_point(g);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(first);
      return unloadablePoint(g, std::max(n, 0), e.what());
    }
    {
      std::lock_guard<std::mutex> lock(first);
      if (n < 0) n = static_cast<int>(in->rig.metronomes.size());
    }
    return runPoint(*in, g, hooks);
  };
  auto finished = [&](const SweepPoint& p) {  // runSweepPoints calls it under its lock
    rows.push_back(p);
    if (on_point) on_point(p);
  };
  const std::function<bool()> stop = [&] { return hooks.stop && hooks.stop(); };
  runSweepPoints(
      grid.size(), [](long) { return true; }, jobs, run, finished, stop);
  std::sort(rows.begin(), rows.end(),
            [](const SweepPoint& a, const SweepPoint& b) { return a.index < b.index; });
  return rows;
}

}  // namespace metrosync
