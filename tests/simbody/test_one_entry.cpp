// One sink and one Simbody entry (issue 24): every full-model run streams into the one RunSink
// (sim/record/run_report.h) -- a single rig's rows, a network's states -- through the one
// Engine::run on both engines, and the Simbody plugin has one run entry for a single rig (the
// network of one, networkOfOne) and a network of platforms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "models/network_equations.h"
#include "models/scaling.h"
#include "sim/engines/engine.h"
#include "sim/engines/simbody/plugin.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

const std::string kRigs = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/";

// Both engines at accuracy 1e-10 agree to ~1e-9 in scaled units over a few periods; a tick
// decided differently or a stick instead of a slip changes the state by O(eps J) ~ 1e-2, so 1e-6
// tells an engine error from integration error with room for the run's growth of the latter.
constexpr double kEnginesAgree = 1e-6;

Network shortNetwork() {
  Network net = loadNetworkFile(kRigs + "two-boards-rollers.yaml");
  net.sim.t_end_s = 3.0;  // ~5 fast periods: ticks on every metronome, the boards stick and slip
  net.sim.accuracy = 1e-10;
  net.sim.integrator.clear();
  return net;
}

// A network's run into the one sink type on both engines: states at the same times, no single
// rig's rows, the same events, the same states to integration error.
TEST(OneSink, MemorySinkTakesANetworkOnBothEngines) {
  const Network net = shortNetwork();
  MemorySink direct, simbody;
  direct.keep_states = simbody.keep_states = true;
  const RunReport d = findEngine("direct")->run(net, direct);
  const RunReport s = findEngine("simbody")->run(net, simbody);
  ASSERT_TRUE(d.complete) << d.failure;
  ASSERT_TRUE(s.complete) << s.failure;
  EXPECT_TRUE(direct.trajectory.empty() && simbody.trajectory.empty());  // no single rig's rows
  EXPECT_TRUE(direct.envelope.empty() && simbody.envelope.empty());
  ASSERT_GE(direct.states.size(), 20u);
  ASSERT_EQ(direct.states.size(), simbody.states.size());
  EXPECT_EQ(direct.states.back().t, net.sim.t_end_s);  // the last one at exactly the end
  EXPECT_EQ(simbody.states.back().t, net.sim.t_end_s);
  EXPECT_EQ(d.counts.escapements, s.counts.escapements);
  EXPECT_EQ(d.counts.stick_slip, s.counts.stick_slip);
  EXPECT_GT(d.counts.stick_slip, 0);

  const ScaledParams sp = computeScaled(net.unionRig());
  const double omega0 = 1.0 / sp.time_scale_s;
  const network::Layout lay = network::NetworkEquations(net).layout();
  for (std::size_t r = 0; r < direct.states.size(); ++r) {
    const MemorySink::State& a = direct.states[r];
    const MemorySink::State& b = simbody.states[r];
    ASSERT_EQ(a.t, b.t) << r;
    EXPECT_EQ(a.modes, b.modes) << "t = " << a.t;
    for (int p = 0; p < lay.platforms; ++p)
      EXPECT_NEAR(a.y[lay.x(p)] / sp.x_scale_m, b.y[lay.x(p)] / sp.x_scale_m, kEnginesAgree);
    for (int j = 0; j < lay.n; ++j) {
      EXPECT_NEAR(a.y[lay.theta(j)] / sp.angle_scale, b.y[lay.theta(j)] / sp.angle_scale,
                  kEnginesAgree)
          << "t = " << a.t << " pendulum " << j;
      EXPECT_NEAR(a.y[lay.omega(j)] / (sp.angle_scale * omega0),
                  b.y[lay.omega(j)] / (sp.angle_scale * omega0), kEnginesAgree)
          << "t = " << a.t << " pendulum " << j;
    }
  }
  EXPECT_EQ(d.final_state, direct.states.back().y);
  EXPECT_EQ(s.final_state, simbody.states.back().y);
}

// The plugin's one entry on a single rig (networkOfOne) into a sink that wants both: the rig's
// rows and the network's states of one run are the same numbers, sample by sample (the rig is
// physical: the rows are SI, as the states).
TEST(SimbodyPlugin, OneEntryRunsASingleRigAndANetwork) {
  const SimbodyPlugin& plugin = *metrosync_simbody_plugin();
  Rig rig = loadRigFile(kRigs + "experiment.yaml");
  ASSERT_EQ(rig.units, Units::Physical);
  rig.sim.t_end_s = 2.0;
  const Network one = networkOfOne(rig);
  MemorySink both;
  both.keep_states = true;
  const RunReport rep = plugin.run(one, both);
  ASSERT_TRUE(rep.complete) << rep.failure;
  ASSERT_GE(both.trajectory.size(), 20u);
  ASSERT_FALSE(both.envelope.empty());
  ASSERT_EQ(both.trajectory.size(), both.states.size());
  const network::Layout lay = network::NetworkEquations(one).layout();
  const int n = static_cast<int>(rig.metronomes.size());
  ASSERT_EQ(lay.n, n);
  for (std::size_t r = 0; r < both.states.size(); ++r) {
    const std::vector<double>& row = both.trajectory[r];  // t, x, xdot, theta_i, thetadot_i, mode
    const MemorySink::State& st = both.states[r];
    ASSERT_EQ(st.t, row[0]) << r;
    EXPECT_EQ(st.y[lay.x(0)], row[1]) << "t = " << row[0];
    EXPECT_EQ(st.y[lay.v(0)], row[2]) << "t = " << row[0];
    for (int j = 0; j < n; ++j) {
      EXPECT_EQ(st.y[lay.theta(j)], row[3 + 2 * j]) << "t = " << row[0];
      EXPECT_EQ(st.y[lay.omega(j)], row[4 + 2 * j]) << "t = " << row[0];
    }
    EXPECT_EQ(static_cast<double>(st.modes[0]), row.back()) << "t = " << row[0];
  }
  EXPECT_EQ(rep.final_trajectory_row, both.trajectory.back());
  EXPECT_EQ(rep.t_end, rig.sim.t_end_s);

  // the same entry on a network of two: its states, no rows in a single rig's format
  MemorySink net;
  net.keep_states = true;
  const RunReport nrep = plugin.run(shortNetwork(), net);
  ASSERT_TRUE(nrep.complete) << nrep.failure;
  EXPECT_TRUE(net.trajectory.empty());
  EXPECT_TRUE(net.events.empty());
  ASSERT_FALSE(net.states.empty());
  EXPECT_EQ(net.states.back().t, nrep.t_end);
  EXPECT_EQ(net.states.back().y, nrep.final_state);
}

}  // namespace
}  // namespace metrosync
