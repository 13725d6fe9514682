// The two full-model engines agree on every shipped rig (yaml/rigs/ and its subfolders: the
// colleagues' yaml/rigs/paper/ and the hard cases in yaml/rigs/hard/ are picked up as they land).
//
// Choice of tolerance: the direct engine runs at accuracy 1e-12 (verner76), which is converged to
// ~1e-12 on these rigs (1e-12 against 1e-14: <= 2e-12); Simbody runs at 1e-14, because its error
// control weighs every coordinate in SI with unit weights, and on rigs with a small epsilon
// (angles ~sqrt(eps), the platform ~eps^{3/2} in SI) its 1e-12 leaves errors of 1e-8..1e-7 in
// scaled units (measured: eps-small, n100, grazing), shrinking 5-7 fold per decade of accuracy.
// Agreement is then required to 1e-8 in scaled units: the envelope rows (A_i, psi_j), the
// pendulums' final angles and rates; the platform's final position and velocity to 1e-7 relative
// to their size (Simbody's weakest variables, measured 1.2e-8 on n100); the event counts exactly.
// A tick decided differently, a stick instead of a slip, or a slip direction changes the state by
// O(eps J) ~ 1e-2.
//
// Choice of window: the dynamics on the slow time scale can be chaotic (psi drifting near a
// saddle), and a 1e-12 difference grows like exp(lambda tau) with lambda = O(1) per unit of slow
// time; 2 units of slow time (at most e^2 growth) keep the comparison about the engines. It is
// also capped at 8 fast periods (plenty of ticks and stick-slip events for a comparison) and, for
// many metronomes, at 64/N periods (not below 1.5, so that there is an envelope row): Simbody's
// cost per period grows with N (n32: ~1 s per period at 1e-12), and the whole test must stay
// within about a minute.
//
// Networks of platforms (docs/networks.md) are compared the same way, sample by sample, on the
// network entries of both (runDirect, runSimbody).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "base/constants.h"
#include "models/network_equations.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;

const std::string kRigRoot = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs";

std::vector<std::string> shippedRigs() {
  std::vector<std::string> rigs;
  for (const auto& e : fs::recursive_directory_iterator(kRigRoot))
    if (e.is_regular_file() && e.path().extension() == ".yaml")
      rigs.push_back(fs::relative(e.path(), kRigRoot).string());
  std::sort(rigs.begin(), rigs.end());
  return rigs;
}

// Rigs the engines cannot be compared on, and why (each is tested on its own elsewhere).
const std::map<std::string, std::string>& notComparable() {
  static const std::map<std::string, std::string> m = {
      {"hard/storm.yaml",
       "an event storm by design: both engines stop it with exit 3 (tests/hard, tests/direct)"},
  };
  return m;
}

class EnginesAgree : public ::testing::TestWithParam<std::string> {};

// Every sample of a network run.
struct NetworkSamples : StateSink {
  std::vector<double> t;
  std::vector<std::vector<double>> y;
  std::vector<std::vector<PlatformMode>> modes;
  void stateSample(double ts, const std::vector<double>& ys,
                   const std::vector<PlatformMode>& ms) override {
    t.push_back(ts);
    y.push_back(ys);
    modes.push_back(ms);
  }
};

// A network (docs/networks.md) on both engines, with the windows and accuracies of the single
// rigs below; every sample compared in scaled units (the scales of the network's first swinging
// metronome): platforms, pendulums to 1e-8 (the bar), modes and counts exactly.
void compareNetworkEngines(const std::string& name) {
  Network net = loadNetworkFile(kRigRoot + "/" + name);
  const ScaledParams sp = computeScaled(net.unionRig());
  const double omega0 = 1.0 / sp.time_scale_s;
  const double periods = std::clamp(64.0 / net.numMetronomes(), 1.5, 8.0);
  net.sim.t_end_s = std::min(2.0 / (sp.epsilon * omega0), periods * kTwoPi / omega0);
  net.sim.integrator.clear();  // Simbody's default
  net.sim.accuracy = 1e-14;
  Network net_direct = net;
  net_direct.sim.integrator = "verner76";
  net_direct.sim.accuracy = 1e-12;

  NetworkSamples sd, ss;
  const RunReport d = runDirect(net_direct, sd);
  const RunReport s = runSimbody(net, ss);
  ASSERT_TRUE(d.complete) << d.failure;
  ASSERT_TRUE(s.complete) << s.failure;
  EXPECT_EQ(s.engine, "simbody");
  EXPECT_EQ(d.counts.escapements, s.counts.escapements);
  EXPECT_EQ(d.counts.stick_slip, s.counts.stick_slip);
  EXPECT_EQ(d.counts.slip_reversals, s.counts.slip_reversals);
  EXPECT_EQ(d.counts.events, s.counts.events);

  const network::Layout lay = network::NetworkEquations(net).layout();
  const double x_unit = sp.x_scale_m, v_unit = sp.x_scale_m * omega0;
  const double a_unit = sp.angle_scale, w_unit = sp.angle_scale * omega0;
  ASSERT_EQ(sd.t, ss.t) << "sample times";
  ASSERT_GE(sd.t.size(), 20u);
  for (std::size_t r = 0; r < sd.y.size(); ++r) {
    const std::vector<double>& a = sd.y[r];
    const std::vector<double>& b = ss.y[r];
    EXPECT_EQ(sd.modes[r], ss.modes[r]) << name << " t = " << sd.t[r];
    for (int p = 0; p < lay.platforms; ++p) {
      EXPECT_NEAR(a[lay.x(p)] / x_unit, b[lay.x(p)] / x_unit, 1e-8) << name << " x " << p;
      EXPECT_NEAR(a[lay.v(p)] / v_unit, b[lay.v(p)] / v_unit, 1e-8) << name << " xdot " << p;
    }
    for (int j = 0; j < lay.n; ++j) {
      EXPECT_NEAR(a[lay.theta(j)] / a_unit, b[lay.theta(j)] / a_unit, 1e-8) << name << " " << j;
      EXPECT_NEAR(a[lay.omega(j)] / w_unit, b[lay.omega(j)] / w_unit, 1e-8) << name << " " << j;
    }
  }
  // both ledgers close, on their own integrations of the dissipation
  EXPECT_LT(std::abs(d.ledger.relativeResidual()), 1e-9);
  EXPECT_LT(std::abs(s.ledger.relativeResidual()), 1e-9);
}

TEST_P(EnginesAgree, OnShippedRig) {
  const std::string name = GetParam();
  if (auto it = notComparable().find(name); it != notComparable().end())
    GTEST_SKIP() << name << ": " << it->second;
  const std::string text = readRigFile(kRigRoot + "/" + name);
  if (isNetworkText(text) && !loadNetworkText(text, name).isSingleRig())
    return compareNetworkEngines(name);
  Rig rig = loadRigFile(kRigRoot + "/" + name);
  const ScaledParams sp = computeScaled(rig);
  const double omega0 = 1.0 / sp.time_scale_s;
  const int n = static_cast<int>(rig.metronomes.size());
  const double periods = std::clamp(64.0 / n, 1.5, 8.0);
  rig.sim.t_end_s = std::min(2.0 / (sp.epsilon * omega0), periods * kTwoPi / omega0);
  rig.sim.integrator.clear();  // Simbody's default
  rig.sim.accuracy = 1e-14;
  Rig rig_direct = rig;
  rig_direct.sim.integrator = "verner76";  // the most accurate per step at 1e-12
  rig_direct.sim.accuracy = 1e-12;

  MemorySink sd, ss;
  const RunReport d = runDirectModel(rig_direct, sd);
  const RunReport s = runSimbody(networkOfOne(rig), ss);
  ASSERT_TRUE(d.complete) << d.failure;
  ASSERT_TRUE(s.complete) << s.failure;

  EXPECT_EQ(d.counts.escapements, s.counts.escapements);
  EXPECT_EQ(d.counts.stick_slip, s.counts.stick_slip);
  EXPECT_EQ(d.counts.slip_reversals, s.counts.slip_reversals);
  EXPECT_EQ(d.counts.events, s.counts.events);
  EXPECT_EQ(sd.events.size(), ss.events.size());

  // final state, scaled units (trajectory rows are in the rig's units)
  const auto& a = d.final_trajectory_row;
  const auto& b = s.final_trajectory_row;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a[0], b[0]) << "end time";
  const bool physical = rig.units == Units::Physical;
  const double x_unit = physical ? sp.x_scale_m : 1.0, a_unit = physical ? sp.angle_scale : 1.0;
  const double t_unit = physical ? sp.time_scale_s : 1.0;
  auto scaled = [&](size_t k, double v) {
    if (k == 1) return v / x_unit;
    if (k == 2) return v / x_unit * t_unit;
    return (k % 2 == 1) ? v / a_unit : v / a_unit * t_unit;  // theta_i odd, thetadot_i even
  };
  for (size_t k = 1; k + 1 < a.size(); ++k) {
    const double va = scaled(k, a[k]), vb = scaled(k, b[k]);
    const double tol = k <= 2 ? 1e-7 * std::max(1.0, std::abs(vb)) : 1e-8;
    EXPECT_NEAR(va, vb, tol) << name << ": column " << k << " of the final row";
  }
  EXPECT_EQ(a.back(), b.back()) << "platform mode at the end";

  ASSERT_EQ(sd.envelope.size(), ss.envelope.size());
  EXPECT_GE(sd.envelope.size(), 1u);
  for (size_t r = 0; r < sd.envelope.size(); ++r) {
    for (size_t i = 0; i < sd.envelope[r].A.size(); ++i)
      EXPECT_NEAR(sd.envelope[r].A[i], ss.envelope[r].A[i], 1e-8) << name << " row " << r;
    for (size_t j = 0; j < sd.envelope[r].psi.size(); ++j)
      EXPECT_NEAR(sd.envelope[r].psi[j], ss.envelope[r].psi[j], 1e-8) << name << " row " << r;
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedRigs, EnginesAgree, ::testing::ValuesIn(shippedRigs()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

}  // namespace
}  // namespace metrosync
