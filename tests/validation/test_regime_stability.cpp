// Issue 15: a regime label must not flip with the run's length. Every shipped example rig
// (yaml/rigs/**, networks aside) is run as shipped and 50% longer, with the slow flow and the full
// model, and must get the same label both times (19 s wall, 9 s CPU here). The sinks judge the run
// as `run` and `sweep` do (the averaged drive for `uncoupled`, the full model's stick/slip rows).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "fixtures.h"
#include "sim/analysis/regime.h"
#include "tools/cli/engines.h"
#include "yaml/network_loader.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;

struct JudgingSink : RunSink {
  JudgingSink(const Rig& rig, const ScaledParams& p, bool full) : window(p.tau_end, p.epsilon) {
    if (!full) window.setEnvelopePlatform(p.friction);
    x_unit = rig.units == Units::Physical ? p.x_scale_m : 1.0;
  }
  void trajectoryRow(const std::vector<double>& row) override {
    window.platformMode(static_cast<int>(row.back()), row[1] / x_unit);
  }
  void eventRow(const char*, const std::vector<double>& row) override { trajectoryRow(row); }
  void envelopeRow(const EnvelopeRow& row) override { window.add(row); }
  RegimeWindow window;
  double x_unit = 1.0;
};

std::string label(const Rig& rig, const std::string& model) {
  const ScaledParams p = computeScaled(rig);
  JudgingSink sink(rig, p, model == "full");
  RunReport rep;
  try {
    rep = cli::chooseEngine("", model, rig, rig.name).run(rig, sink);
  } catch (const SimulationFailure&) {
    return "unknown";
  }
  if (!rep.complete) return "unknown";
  return regimeName(classifyRegime(sink.window, p.theta_c, p.locked));
}

TEST(RegimeStability, EveryShippedRigKeepsItsLabelWhenRunHalfAgainAsLong) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(testval::rigsDir()))
    if (e.path().extension() == ".yaml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  int judged = 0, full_runs = 0;
  for (const auto& file : files) {
    if (isNetworkText(readRigFile(file))) continue;  // networks: per-platform verdicts
    const Rig rig = loadRigFile(file);
    Rig longer = rig;
    longer.sim.t_end_s *= 1.5;
    ASSERT_NEAR(computeScaled(longer).tau_end, 1.5 * computeScaled(rig).tau_end,
                1e-9 * computeScaled(rig).tau_end)
        << file;
    for (const std::string model : {"slow", "full"}) {
      SCOPED_TRACE(file + " (" + model + ")");
      const std::string base = label(rig, model), longer_label = label(longer, model);
      EXPECT_EQ(base, longer_label);
      ++judged;
      full_runs += model == "full";
    }
  }
  EXPECT_GE(judged, 74);  // 37 rigs (networks aside), both models
  EXPECT_GE(full_runs, 37);
}

}  // namespace
}  // namespace metrosync
