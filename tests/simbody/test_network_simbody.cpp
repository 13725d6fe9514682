// The Simbody engine on networks of platforms (docs/networks.md, issue 13), each test against an
// independent truth: the single-platform Simbody engine (k = 0 decouples the network), the direct
// network engine on a stack (the shipped rigs have none; tests/direct/test_agreement.cpp compares
// the shipped ones), and conservation laws (momentum and the energy ledger of a network with no
// friction to the table and no ground spring).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "models/network_equations.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "yaml/network_loader.h"

namespace metrosync {
namespace {

std::string num(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// A metronome of the paper's experiment (yaml/rigs/experiment.yaml) started at `angle`, `rate`.
std::string metronome(double angle, double rate, double length = 0.0225) {
  return "      - {box_mass: 0.0602, pendulum: {mass: 0.0226, length: " + num(length) +
         ", decay_rate: 0.5}, escapement: {angle: 0.244, steady_amplitude: 0.785}, start: "
         "{angle: " +
         num(angle) + ", rate: " + num(rate) + "}}\n";
}

std::string platform(const std::string& name, const std::string& friction, const std::string& extra,
                     const std::string& metronomes) {
  return "  - name: " + name + "\n    mass: 0.1432\n    friction: " + friction + "\n" + extra +
         "    metronomes:\n" + metronomes;
}

std::string network(const std::string& platforms, const std::string& couplings, double duration,
                    double accuracy) {
  return "units: physical\nplatforms:\n" + platforms + couplings +
         "simulation: {duration: " + num(duration) + ", accuracy: " + num(accuracy) + "}\n";
}

struct Samples : StateSink {
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

// The bar for a network against its parts, at accuracy 1e-12 (SI units).
constexpr double kAgree = 1e-8;

TEST(NetworkSimbody, ZeroCouplingDecouplesIntoSinglePlatformRuns) {
  const std::string left = platform("left", "{law: coulomb, mu: 6.5e-4}", "",
                                    metronome(0.785, 0.0) + metronome(-0.785, 0.25));
  const std::string right = platform("right", "{law: viscous, c: 0.02}", "    spring: {k: 3.0}\n",
                                     metronome(0.6, 0.1, 0.03));
  const Network net = loadNetworkText(
      network(left + right, "couplings:\n  - {between: [left, right], k: 0.0}\n", 3.0, 1e-12),
      "k0.yaml");
  Samples sink;
  const RunReport rep = runSimbody(net, sink);
  ASSERT_TRUE(rep.complete) << rep.failure;
  const network::Layout lay = network::NetworkEquations(net).layout();
  int j = 0;
  long stick_slip = 0;
  for (int p = 0; p < 2; ++p) {
    MemorySink one;
    const RunReport single = runSimbody(networkOfOne(net.platforms[p].rig), one);  // Simbody, alone
    ASSERT_TRUE(single.complete) << single.failure;
    stick_slip += single.counts.stick_slip;
    const std::vector<double>& row = single.final_trajectory_row;  // t, x, xdot, theta, thetadot..
    ASSERT_EQ(row[0], rep.t_end);
    EXPECT_NEAR(rep.final_state[lay.x(p)], row[1], kAgree) << "platform " << p;
    EXPECT_NEAR(rep.final_state[lay.v(p)], row[2], kAgree) << "platform " << p;
    for (std::size_t i = 0; i < net.platforms[p].rig.metronomes.size(); ++i, ++j) {
      EXPECT_NEAR(rep.final_state[lay.theta(j)], row[3 + 2 * i], kAgree) << "pendulum " << j;
      EXPECT_NEAR(rep.final_state[lay.omega(j)], row[4 + 2 * i], kAgree) << "pendulum " << j;
      EXPECT_EQ(rep.counts.escapements[j], single.counts.escapements[i]) << "pendulum " << j;
    }
  }
  EXPECT_EQ(rep.counts.stick_slip, stick_slip);
  EXPECT_GT(rep.counts.stick_slip, 0);  // the Coulomb board did stick and slip
}

// The limiting case: a network of one platform on the table is the single rig. Both go through the
// one Simbody system builder and run loop, so they agree bit for bit: every sample (time, board,
// pendulums, mode), the counts and the ledger.
TEST(NetworkSimbody, OnePlatformNetworkIsTheSingleRig) {
  const std::string board =
      platform("board", "{law: coulomb, mu: 0.004}", "    spring: {k: 2.0}\n",
               metronome(0.785, 0.0) + metronome(-0.6, 0.25) + metronome(0.3, 0.1, 0.03));
  const Network net = loadNetworkText(network(board, "", 3.0, 1e-10), "one.yaml");
  ASSERT_EQ(net.platforms.size(), 1u);
  Samples sink;
  const RunReport rep = runSimbody(net, sink);
  MemorySink one;
  const RunReport single = runSimbody(networkOfOne(net.platforms[0].rig), one);
  ASSERT_TRUE(rep.complete) << rep.failure;
  ASSERT_TRUE(single.complete) << single.failure;
  EXPECT_GT(rep.counts.stick_slip, 2);  // the board did stick and slip
  EXPECT_EQ(rep.counts.stick_slip, single.counts.stick_slip);
  EXPECT_EQ(rep.counts.slip_reversals, single.counts.slip_reversals);
  EXPECT_EQ(rep.counts.escapements, single.counts.escapements);
  EXPECT_EQ(rep.counts.steps, single.counts.steps);
  EXPECT_EQ(rep.ledger.escapement_in_J, single.ledger.escapement_in_J);
  EXPECT_EQ(rep.ledger.friction_out_J, single.ledger.friction_out_J);
  const network::Layout lay = network::NetworkEquations(net).layout();
  ASSERT_EQ(sink.t.size(), one.trajectory.size());
  for (std::size_t r = 0; r < sink.t.size(); ++r) {
    const std::vector<double>& row = one.trajectory[r];  // t, x, xdot, theta, thetadot.., mode
    ASSERT_EQ(sink.t[r], row[0]) << r;
    EXPECT_EQ(sink.y[r][lay.x(0)], row[1]) << "t = " << row[0];
    EXPECT_EQ(sink.y[r][lay.v(0)], row[2]) << "t = " << row[0];
    for (int j = 0; j < lay.n; ++j) {
      EXPECT_EQ(sink.y[r][lay.theta(j)], row[3 + 2 * j]) << "t = " << row[0] << " " << j;
      EXPECT_EQ(sink.y[r][lay.omega(j)], row[4 + 2 * j]) << "t = " << row[0] << " " << j;
    }
    EXPECT_EQ(static_cast<int>(sink.modes[r][0]), static_cast<int>(row.back())) << row[0];
  }
}

// Momentum P = sum_p (M_p xdot_p + sum_j m_j L_j cos theta_j thetadot_j) of every sample.
void expectMomentumConserved(const Network& net, const Samples& sink) {
  const network::NetworkEquations eq(net);
  const double P0 = eq.momentum(sink.y.front().data());
  // relative to the momentum's natural size: one pendulum's m L times its typical rate (rad/s)
  const double scale = 0.0226 * 0.0225 * 3.0;
  for (std::size_t r = 0; r < sink.y.size(); ++r)
    ASSERT_NEAR(eq.momentum(sink.y[r].data()), P0, 1e-9 * scale) << "t = " << sink.t[r];
}

TEST(NetworkSimbody, FrictionlessNetworkConservesMomentumAndClosesItsLedger) {
  // two boards on a frictionless table (mu = 0), no ground spring, joined by a spring and damper
  const std::string a =
      platform("a", "{law: coulomb, mu: 0.0}", "", metronome(0.785, 0.0) + metronome(-0.5, 0.3));
  const std::string b = platform("b", "{law: coulomb, mu: 0.0}", "", metronome(0.6, -0.2));
  const Network net = loadNetworkText(
      network(a + b, "couplings:\n  - {between: [a, b], k: 5.0, c: 0.01}\n", 5.0, 1e-12),
      "pair.yaml");
  Samples sink;
  const RunReport rep = runSimbody(net, sink);
  ASSERT_TRUE(rep.complete) << rep.failure;
  long ticks = 0;
  for (long t : rep.counts.escapements) ticks += t;
  EXPECT_GT(ticks, 10);  // the escapements did act
  expectMomentumConserved(net, sink);
  EXPECT_LT(std::abs(rep.ledger.relativeResidual()), 1e-9) << rep.ledger.residual_J();
  EXPECT_GT(rep.ledger.damping_out_J, 0.0);
}

// `top` rests on `base` (Coulomb between them); base on the table with `base_friction`.
Network stack(const std::string& base_friction, double duration, double accuracy,
              const std::string& side = "", const std::string& couplings = "") {
  const std::string base =
      platform("base", base_friction, "", metronome(0.785, 0.0) + metronome(-0.785, 0.25));
  const std::string top =
      platform("top", "{law: coulomb, mu: 0.02}", "    on: base\n", metronome(0.5, -0.3, 0.03));
  return loadNetworkText(network(base + top + side, couplings, duration, accuracy), "stack.yaml");
}

TEST(NetworkSimbody, StackThatSlipsConservesMomentumAndClosesItsLedger) {
  // the contact between the boards is internal: momentum is conserved through every switch
  const Network net = stack("{law: none}", 5.0, 1e-12);
  Samples sink;
  const RunReport rep = runSimbody(net, sink);
  ASSERT_TRUE(rep.complete) << rep.failure;
  EXPECT_GT(rep.counts.stick_slip, 2);  // the contact did switch
  expectMomentumConserved(net, sink);
  EXPECT_LT(std::abs(rep.ledger.relativeResidual()), 1e-9) << rep.ledger.residual_J();
  EXPECT_GT(rep.ledger.friction_out_J, 0.0);
}

TEST(NetworkSimbody, StackStuckThroughoutIsOnePlatformWithBoth) {
  // `top` on `base` with a friction that never lets go: the pair is one board of both masses
  // carrying all three metronomes (the single-platform Simbody engine)
  // (the base sticks and slips: while both contacts stick, their holding forces come from one
  // solve)
  const std::string base = platform("base", "{law: coulomb, mu: 0.005}", "",
                                    metronome(0.785, 0.0) + metronome(-0.785, 0.25));
  const std::string top =
      platform("top", "{law: coulomb, mu: 1.0e4}", "    on: base\n", metronome(0.5, -0.3, 0.03));
  const Network net = loadNetworkText(network(base + top, "", 3.0, 1e-12), "stack.yaml");
  Samples sink;
  const RunReport rep = runSimbody(net, sink);
  ASSERT_TRUE(rep.complete) << rep.failure;
  Rig both = net.platforms[0].rig;
  both.platform.mass_kg += net.platforms[1].rig.platform.mass_kg;
  for (const MetronomeSpec& m : net.platforms[1].rig.metronomes) both.metronomes.push_back(m);
  MemorySink one;
  const RunReport single = runSimbody(networkOfOne(both), one);
  ASSERT_TRUE(single.complete) << single.failure;
  EXPECT_EQ(rep.counts.stick_slip, single.counts.stick_slip);
  EXPECT_GT(rep.counts.stick_slip, 0);
  const std::vector<double>& row = single.final_trajectory_row;
  const network::Layout lay = network::NetworkEquations(net).layout();
  EXPECT_NEAR(rep.final_state[lay.x(0)], row[1], kAgree);
  EXPECT_NEAR(rep.final_state[lay.x(1)], row[1], kAgree);  // the top never slipped
  EXPECT_NEAR(rep.final_state[lay.v(0)], row[2], kAgree);
  EXPECT_NEAR(rep.final_state[lay.v(1)], row[2], kAgree);
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(rep.final_state[lay.theta(j)], row[3 + 2 * j], kAgree) << j;
    EXPECT_NEAR(rep.final_state[lay.omega(j)], row[4 + 2 * j], kAgree) << j;
  }
}

// At every sample each Coulomb contact is consistent with its mode: a stuck one holds within its
// bound (left beyond it by a window, its witness would never cross again), a slipping one moves
// its own way (friction never pushes a slip along: a reversal inside a step was missed).
void expectConsistentContacts(const Network& net, const Samples& run) {
  const network::NetworkEquations eq(net);
  for (std::size_t r = 0; r < run.y.size(); ++r) {
    const std::vector<double> h = eq.holdingForces(run.y[r].data(), run.modes[r]);
    for (int p = 0; p < eq.numPlatforms(); ++p) {
      if (!eq.block(p).moves || !eq.block(p).friction.setValued()) continue;
      if (eq.stuck(p, run.modes[r]))
        EXPECT_LT(std::abs(h[p]), eq.block(p).friction.bounds().staticBound() * (1 + 1e-9))
            << "platform " << p << " t = " << run.t[r];
      else
        EXPECT_GE(static_cast<int>(run.modes[r][p]) * eq.slipVelocity(run.y[r].data(), p), 0.0)
            << "platform " << p << " t = " << run.t[r];
    }
  }
}

// Both network engines on `net` (Simbody at `simbody_accuracy`, direct verner76 at 1e-12): the
// counts exactly, every sample to 1e-8 in scaled units, every contact consistent.
void expectEnginesAgree(const Network& net, double simbody_accuracy, long min_switches) {
  Network net_simbody = net, net_direct = net;
  net_simbody.sim.accuracy = simbody_accuracy;
  net_simbody.sim.integrator.clear();
  net_direct.sim.accuracy = 1e-12;
  net_direct.sim.integrator = "verner76";
  Samples sd, ss;
  const RunReport d = runDirect(net_direct, sd);
  const RunReport s = runSimbody(net_simbody, ss);
  ASSERT_TRUE(d.complete) << d.failure;
  ASSERT_TRUE(s.complete) << s.failure;
  EXPECT_GE(d.counts.stick_slip + d.counts.slip_reversals, min_switches);
  EXPECT_EQ(d.counts.escapements, s.counts.escapements);
  EXPECT_EQ(d.counts.stick_slip, s.counts.stick_slip);
  EXPECT_EQ(d.counts.slip_reversals, s.counts.slip_reversals);
  EXPECT_EQ(d.counts.events, s.counts.events);
  expectConsistentContacts(net, sd);
  expectConsistentContacts(net, ss);
  const ScaledParams sp = computeScaled(net.unionRig());
  const double omega0 = 1.0 / sp.time_scale_s;
  const network::Layout lay = network::NetworkEquations(net).layout();
  ASSERT_EQ(sd.t, ss.t);
  for (std::size_t r = 0; r < sd.y.size(); ++r) {
    EXPECT_EQ(sd.modes[r], ss.modes[r]) << "t = " << sd.t[r];
    for (int p = 0; p < lay.platforms; ++p) {
      EXPECT_NEAR(sd.y[r][lay.x(p)], ss.y[r][lay.x(p)], 1e-8 * sp.x_scale_m) << p;
      EXPECT_NEAR(sd.y[r][lay.v(p)], ss.y[r][lay.v(p)], 1e-8 * sp.x_scale_m * omega0) << p;
    }
    for (int j = 0; j < lay.n; ++j) {
      EXPECT_NEAR(sd.y[r][lay.theta(j)], ss.y[r][lay.theta(j)], 1e-8 * sp.angle_scale) << j;
      EXPECT_NEAR(sd.y[r][lay.omega(j)], ss.y[r][lay.omega(j)], 1e-8 * sp.angle_scale * omega0)
          << j;
    }
  }
}

TEST(NetworkSimbody, FixedPlatformsAgreeWithTheDirectEngine) {
  // a board resting on a fixed one (its contact slips both ways, some slips reversing within a
  // step of either engine after starting from rest), a free board coupled to both
  const std::string wall = platform("wall", "{law: fixed}", "", metronome(0.785, 0.0));
  const std::string top = platform("top", "{law: coulomb, mu: 0.003}", "    on: wall\n",
                                   metronome(0.3, -2.0, 0.0227) + metronome(-0.5, 1.0));
  const std::string free =
      "  - name: free\n    mass: 0.2\n    friction: {law: none}\n"
      "    start: {x: 0.01, v: 0.02}\n    metronomes:\n" +
      metronome(0.6, 0.5, 0.023);
  const Network net =
      loadNetworkText(network(wall + top + free,
                              "couplings:\n  - {between: [wall, free], k: 3.0, c: 0.01}\n"
                              "  - {between: [top, free], k: 1.0}\n",
                              4.0, 1e-12),
                      "fixed.yaml");
  expectEnginesAgree(net, 1e-13, 20);
}

TEST(NetworkSimbody, TowerOfThreeListedTopFirstAgreesWithTheDirectEngine) {
  // c on b on a, listed c, a, b: the sliders are built bottom up whatever the file order; three
  // Coulomb contacts, often all stuck at once (three holding forces from one solve)
  const std::string c =
      "  - name: c\n    on: b\n    mass: 0.1\n    friction: {law: coulomb, "
      "mu: 0.01}\n    metronomes:\n" +
      metronome(0.6, 1.0, 0.022);
  const std::string a =
      platform("a", "{law: coulomb, mu: 0.002}", "", metronome(0.785, 0.0) + metronome(-0.5, 1.0));
  const std::string b =
      "  - name: b\n    on: a\n    mass: 0.12\n    friction: {law: coulomb, "
      "mu: 0.005}\n    metronomes:\n" +
      metronome(0.3, -2.0, 0.0227);
  const Network net = loadNetworkText(network(c + a + b, "", 4.0, 1e-12), "tower.yaml");
  expectEnginesAgree(net, 1e-13, 50);
}

TEST(NetworkSimbody, StackAgreesWithTheDirectEngine) {
  // both contacts Coulomb (often stuck together: holding forces from one solve), a third board
  // on a ground spring and damper, coupled to the base
  const std::string side =
      "  - name: side\n    mass: 0.2\n    friction: {law: viscous, c: 0.02}\n"
      "    spring: {k: 3.0, c: 0.01}\n    metronomes:\n" +
      metronome(0.3, 0.1);
  const Network net = stack("{law: coulomb, mu: 6.5e-4}", 3.0, 1e-12, side,
                            "couplings:\n  - {between: [base, side], k: 2.0, c: 0.005}\n");
  expectEnginesAgree(net, 1e-13, 10);
}

TEST(NetworkSimbody, StribeckBoardOfTwoAgreesWithTheDirectEngine) {
  // Stribeck friction (contact/stribeck.cpp): static twice kinetic, falling over 2 mm/s, about
  // the board's own speed; two metronomes out of phase make it stick and slip. A second board
  // (Coulomb, one metronome) on a weak spring to it: on a network of one platform alone the
  // direct network model counts its events apart from Simbody's (166 against 75 for static
  // friction too; issue 38's "One model" merges the two direct models)
  const std::string board =
      platform("board", "{law: stribeck, mu: 6.5e-4, mu_static: 1.3e-3, stribeck_velocity: 2e-3}",
               "", metronome(0.785, 0.0) + metronome(-0.5, 1.0));
  const std::string other =
      platform("other", "{law: coulomb, mu: 6.5e-4}", "", metronome(0.6, 0.3));
  const Network net = loadNetworkText(
      network(board + other, "couplings:\n  - {between: [board, other], k: 0.5}\n", 4.0, 1e-12),
      "stribeck.yaml");
  expectEnginesAgree(net, 1e-13, 10);
}

}  // namespace
}  // namespace metrosync
