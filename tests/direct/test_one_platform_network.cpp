// The limiting case of the one model (issue 24): a network of one platform on the table, no
// coupling, no ground damper, is the single rig. The network's general equations
// (models/network_equations.h, composing each platform's arrow and solving the stuck contacts'
// holding forces) against its single-board entries (the arrow's fused pass with one platform mode,
// the closed-form holding force) on random states in every contact mode, and its run on the
// network's model against the single rig's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "models/network_equations.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/engine.h"
#include "yaml/network_loader.h"

namespace metrosync {
namespace {

// Two metronomes of the paper's experiment (yaml/rigs/experiment.yaml), one with a longer
// pendulum, on one board with the given friction and a ground spring.
std::string board(const std::string& friction, double duration) {
  const std::string m =
      "      - {box_mass: 0.0602, pendulum: {mass: 0.0226, length: LEN, decay_rate: 0.5}, "
      "escapement: {angle: 0.244, steady_amplitude: 0.785}, start: {angle: ANG, rate: 0.1}}\n";
  auto metronome = [&](const std::string& len, const std::string& ang) {
    std::string s = m;
    s.replace(s.find("LEN"), 3, len);
    s.replace(s.find("ANG"), 3, ang);
    return s;
  };
  return "units: physical\nplatforms:\n  - name: only\n    mass: 0.1432\n    friction: " +
         friction + "\n    spring: {k: 2.0}\n    metronomes:\n" + metronome("0.0225", "0.785") +
         metronome("0.03", "-0.6") + "simulation: {duration: " + std::to_string(duration) +
         ", accuracy: 1e-12}\n";
}

// Round-off of the two evaluation orders: the network adds the platform's push, friction and
// its contact's holding force in other steps than the single rig (a stuck contact's zero
// acceleration comes out of a 1 x 1 solve, to a few ulps); 1e-13 of each kind's size is
// hundreds of ulps and a millionth of any modelling difference.
constexpr double kRoundOff = 1e-13;

// max |y_i| over [begin, end)
double size(const std::vector<double>& y, int begin, int end) {
  double s = 0.0;
  for (int i = begin; i < end; ++i) s = std::max(s, std::abs(y[i]));
  return s;
}

void expectSameRates(const std::string& friction, PlatformMode mode) {
  const Network net = loadNetworkText(board(friction, 1.0), "one.yaml");
  ASSERT_EQ(net.platforms.size(), 1u);
  const network::NetworkEquations nq(net);
  ASSERT_TRUE(nq.singleArrow());
  const network::NetworkEquations& sq = nq;  // its single-board entries
  const network::Layout lay = nq.layout();
  const network::Layout sl = lay;
  ASSERT_FALSE(lay.dampers);
  ASSERT_EQ(lay.dim(), 4 + 2 * lay.n);  // the layout the single rig always had
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> ys(sl.dim(), 0.0), yn(lay.dim(), 0.0);
    ys[sl.x(0)] = 0.01 * u(gen);
    ys[sl.v(0)] = mode == PlatformMode::Stuck ? 0.0 : 0.05 * u(gen);
    for (int j = 0; j < sl.n; ++j) {
      ys[sl.theta(j)] = 1.2 * u(gen);
      ys[sl.omega(j)] = 5.0 * u(gen);
    }
    yn[lay.x(0)] = ys[sl.x(0)];
    yn[lay.v(0)] = ys[sl.v(0)];
    for (int j = 0; j < sl.n; ++j) {
      yn[lay.theta(j)] = ys[sl.theta(j)];
      yn[lay.omega(j)] = ys[sl.omega(j)];
    }
    std::vector<double> ds(sl.dim()), dn(lay.dim());
    sq.rhs(ys.data(), mode, ds.data());
    // the general equations (a braced {mode} would pick the single-board overload)
    nq.rhs(yn.data(), std::vector<PlatformMode>{mode}, dn.data());
    const double a_size =
        std::max(std::abs(ds[sl.v(0)]), size(ds, sl.omega(0), sl.omega(0) + sl.n) * 1e-3);
    EXPECT_EQ(dn[lay.x(0)], ds[sl.x(0)]);
    EXPECT_NEAR(dn[lay.v(0)], ds[sl.v(0)], kRoundOff * a_size) << trial;
    const double dw_size = size(ds, sl.omega(0), sl.omega(0) + sl.n);
    for (int j = 0; j < sl.n; ++j) {
      EXPECT_EQ(dn[lay.theta(j)], ds[sl.theta(j)]) << trial << " " << j;
      EXPECT_NEAR(dn[lay.omega(j)], ds[sl.omega(j)], kRoundOff * dw_size) << trial << " " << j;
    }
    EXPECT_EQ(dn[lay.dampingWork()], ds[sl.dampingWork()]) << trial;
    EXPECT_NEAR(dn[lay.frictionWork()], ds[sl.frictionWork()],
                kRoundOff * std::abs(ds[sl.frictionWork()]))
        << trial;
    // the energy and an impulse are the arrow's own arithmetic: the same bits
    EXPECT_EQ(nq.energy(yn.data()), sq.energy(ys.data())) << trial;
    const std::vector<double> pin = {1e-4 * u(gen), 1e-4 * u(gen)};
    const double contact = 1e-3 * u(gen);
    EXPECT_EQ(nq.applyImpulse(yn.data(), pin, {contact}),
              sq.applyImpulse(ys.data(), pin.data(), contact));
    EXPECT_EQ(yn[lay.v(0)], ys[sl.v(0)]);
    for (int j = 0; j < sl.n; ++j) EXPECT_EQ(yn[lay.omega(j)], ys[sl.omega(j)]) << j;
    EXPECT_EQ(nq.contactMobility(yn.data(), 0), sq.platformMobility(ys.data()));
    if (mode == PlatformMode::Stuck && friction.find("coulomb") != std::string::npos) {
      yn[lay.v(0)] = ys[sl.v(0)] = 0.0;
      const double h = sq.holdingForce(ys.data());
      EXPECT_NEAR(nq.holdingForces(yn.data(), {mode})[0], h, kRoundOff * std::abs(h)) << trial;
    }
  }
}

TEST(OnePlatformNetwork, EquationsAreTheSingleRigsInEveryCoulombMode) {
  for (PlatformMode mode :
       {PlatformMode::Stuck, PlatformMode::SlipPositive, PlatformMode::SlipNegative})
    expectSameRates("{law: coulomb, mu: 6.5e-4}", mode);
}

TEST(OnePlatformNetwork, EquationsAreTheSingleRigsWithViscousAndNoFriction) {
  expectSameRates("{law: viscous, c: 0.02}", PlatformMode::Stuck);
  expectSameRates("{law: none}", PlatformMode::Stuck);
}

struct LastState : StateSink {
  void stateSample(double, const std::vector<double>&, const std::vector<PlatformMode>&) override {}
};

// The two runs of the same board agree to their accuracy: at 1e-12, three seconds with stick-slip
// and ticks, measured 3.4e-12 apart at most (a pendulum's; the platform's x and xdot 1.2e-14).
// Not round-off: one run and one model (sim/engines/direct/direct_model.h) in its two kinds, the
// network's general equations and steps of at most 0.05 of a period (DirectOptions::
// general_equations) against the single board's fused entry with N known to the compiler and
// steps of a tenth of its fastest oscillation.
TEST(OnePlatformNetwork, RunsAsTheSingleRig) {
  const Network net = loadNetworkText(board("{law: coulomb, mu: 1e-4}", 3.0), "one.yaml");
  ASSERT_TRUE(net.isSingleRig());
  LastState sink;
  DirectOptions general;
  general.general_equations = true;  // the board run as any network is
  const RunReport nrep = runDirect(net, sink, general);
  ASSERT_TRUE(nrep.complete) << nrep.failure;
  MemorySink one;
  const RunReport srep = runDirectModel(net.toSingleRig(), one);
  ASSERT_TRUE(srep.complete) << srep.failure;
  // one start-state construction (sim/engines/direct/start_state.h), the same equations: the
  // start's energy (after the contact's mode is settled at rest) is the same bits
  EXPECT_EQ(nrep.ledger.initial_J, srep.ledger.initial_J);
  EXPECT_GT(srep.counts.slip_reversals, 0);  // the board slid both ways
  EXPECT_EQ(nrep.counts.slip_reversals, srep.counts.slip_reversals);
  EXPECT_EQ(nrep.counts.stick_slip, srep.counts.stick_slip);
  const std::vector<double>& row = srep.final_trajectory_row;  // t, x, xdot, theta_i, thetadot_i
  const network::Layout lay = network::NetworkEquations(net).layout();
  constexpr double kAgree = 1e-11;  // 3x the measured gap
  EXPECT_NEAR(nrep.final_state[lay.x(0)], row[1], kAgree);
  EXPECT_NEAR(nrep.final_state[lay.v(0)], row[2], kAgree);
  for (int j = 0; j < lay.n; ++j) {
    EXPECT_NEAR(nrep.final_state[lay.theta(j)], row[3 + 2 * j], kAgree) << j;
    EXPECT_NEAR(nrep.final_state[lay.omega(j)], row[4 + 2 * j], kAgree) << j;
  }
  for (int i = 0; i < lay.n; ++i)
    EXPECT_EQ(nrep.counts.escapements[i], srep.counts.escapements[i]) << i;
}

// The sink does not choose the model (issue 38): a single rig run through the engines' one entry
// into a sink that wants its states runs the rig's own model, the same steps and evaluations as
// into a sink of rows only, and its states are its rows' numbers, sample by sample (the rig is
// physical: rows and states are SI). On main a sink of states ran the network's model (other steps,
// and no rows).
TEST(OnePlatformNetwork, TheSinkDoesNotChooseTheModel) {
  const Network net = loadNetworkText(board("{law: coulomb, mu: 1e-4}", 3.0), "one.yaml");
  ASSERT_TRUE(net.isSingleRig());
  const Engine& direct = *findEngine("direct");
  MemorySink rows, both;
  both.keep_states = true;
  const RunReport a = direct.run(net, rows);
  const RunReport b = direct.run(net, both);
  ASSERT_TRUE(a.complete && b.complete) << a.failure << b.failure;
  EXPECT_EQ(a.counts.steps, b.counts.steps);
  EXPECT_EQ(a.counts.rhs_evals, b.counts.rhs_evals);
  EXPECT_EQ(a.counts.slip_reversals, b.counts.slip_reversals);
  EXPECT_GT(b.counts.slip_reversals, 0);  // the board slid both ways
  EXPECT_EQ(rows.trajectory, both.trajectory);
  EXPECT_TRUE(rows.states.empty());
  ASSERT_GE(both.states.size(), 20u);
  ASSERT_EQ(both.states.size(), both.trajectory.size());
  const network::Layout lay = network::NetworkEquations(net).layout();
  EXPECT_FALSE(lay.dampers);  // no damper: no slot for its work
  for (std::size_t r = 0; r < both.states.size(); ++r) {
    const MemorySink::State& s = both.states[r];
    const std::vector<double>& row = both.trajectory[r];  // t, x, xdot, theta_i, thetadot_i, mode
    ASSERT_EQ(s.y.size(), static_cast<std::size_t>(lay.dim()));
    EXPECT_EQ(s.t, row[0]) << r;
    EXPECT_EQ(s.y[lay.x(0)], row[1]) << r;
    EXPECT_EQ(s.y[lay.v(0)], row[2]) << r;
    for (int j = 0; j < lay.n; ++j) {
      EXPECT_EQ(s.y[lay.theta(j)], row[3 + 2 * j]) << r;
      EXPECT_EQ(s.y[lay.omega(j)], row[4 + 2 * j]) << r;
    }
    ASSERT_EQ(s.modes.size(), 1u);
    EXPECT_EQ(static_cast<double>(static_cast<int>(s.modes[0])), row.back()) << r;
  }
  EXPECT_EQ(both.states.back().t, net.sim.t_end_s);
  EXPECT_EQ(b.final_state, both.states.back().y);
}

}  // namespace
}  // namespace metrosync
