// A fold of cycles, found by `metrosync continue` and checked again here by an integration that
// shares nothing with the continuation: the frictionless pair f4.1 in mu from 0.05 (--all) has a
// subcritical Hopf point near mu = 0.618 whose unstable cycle turns into a stable one at a fold
// near mu = 0.627. The command must report the fold confirmed; then classical RK4 on the slow
// flow's complex amplitudes (modes held: the cycles stay inside one region) from the reported
// state on the stable cycle nearest the fold returns to it after ten periods, while at the mirror
// value of mu beyond the fold the same start does not (no cycle there).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "models/scaling.h"
#include "models/slow_flow.h"
#include "tests/common/run_metrosync.h"
#include "tests/continuation/fixtures.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;
using Cd = std::complex<double>;

const std::string kRig = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/paper/f4.1.yaml";

ScaledParams f41(double mu) {
  char kv[64];
  std::snprintf(kv, sizeof kv, "platform.friction.mu=%.17g", mu);
  return computeScaled(loadRigFile(kRig, {kv}));
}

// Distance between two states up to the common phase.
double distance(const std::vector<Cd>& a, const std::vector<Cd>& b) {
  const Cd turn = std::polar(1.0, std::arg(a[0]) - std::arg(b[0]));
  return std::max(std::abs(b[0] * turn - a[0]), std::abs(b[1] * turn - a[1]));
}

struct CycleRow {
  double mu = 0, period = 0;
  bool stable = false;
  std::vector<Cd> z;  // the state on the cycle
};

std::vector<CycleRow> cycleRows(const std::string& path, int cycle) {
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);  // cycle,KEY,period,A_1_min,A_1_max,A_2_min,A_2_max,psi_2_min,psi_2_max,
                           // stable,max_multiplier,A_1_0,A_2_0,psi_2_0
  std::vector<CycleRow> rows;
  while (std::getline(in, line)) {
    std::vector<double> c;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(std::stod(cell));
    if (static_cast<int>(c[0]) != cycle) continue;
    rows.push_back({c[1], c[2], c[9] == 1, {Cd(c[11]), std::polar(c[12], -c[13])}});
  }
  return rows;
}

TEST(CycleFold, ConfirmedByTheSlowFlowAndByAnIndependentIntegration) {
  const std::string out = scratchDir("continue", "cycle-fold");
  const auto r = runMetrosync("continue " + shellQuote(kRig) +
                              " --param platform.friction.mu --from 0.05 --to 1 --all -q --out " +
                              shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto summary = nlohmann::json::parse(slurp(out + "/summary.json"));
  int cycle = -1;
  double mu_f = 0;
  for (const auto& c : summary["cycles"])
    for (const auto& f : c["folds"])
      if (f["confirmed"].get<bool>()) cycle = c["cycle"], mu_f = f["value"];
  ASSERT_GE(cycle, 0) << summary["cycles"];
  EXPECT_NEAR(mu_f, 0.627, 0.01);
  // the stable cycle nearest the fold, and the mirror value beyond it
  const std::vector<CycleRow> rows = cycleRows(out + "/cycles.csv", cycle);
  const CycleRow* s = nullptr;
  for (const CycleRow& q : rows)
    if (q.stable && (!s || std::abs(q.mu - mu_f) < std::abs(s->mu - mu_f))) s = &q;
  ASSERT_NE(s, nullptr);
  const double mu_b = 2 * mu_f - s->mu;
  const ScaledParams on = f41(s->mu), off = f41(mu_b);
  const SlowFlowModes modes = slowFlowModesAt(on, s->z);
  const int steps = 2000;  // per period: RK4's error ~ (T / 2000)^4, far below the tolerances
  EXPECT_LT(
      distance(continuation::testing::rk4SlowFlow(on, modes, s->z, 10 * s->period, 10 * steps),
               s->z),
      1e-3);
  double off_distance = 0;
  std::vector<Cd> z = s->z;
  for (int k = 0; k < 150 && off_distance < 0.1; ++k) {
    z = continuation::testing::rk4SlowFlow(off, modes, z, s->period, steps);
    off_distance = std::max(off_distance, distance(z, s->z));
  }
  EXPECT_GT(off_distance, 0.1);
}

}  // namespace
}  // namespace metrosync
