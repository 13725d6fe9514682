// Kuramoto order parameter and the network label (docs/networks.md) against closed forms:
// identical phases give r = 1; independent uniform phases give E[r^2] = 1/n exactly; the labels
// on groups built to be each case.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "base/constants.h"
#include "sim/analysis/network_regime.h"
#include "sim/analysis/order_parameter.h"
#include "sim/analysis/regime.h"
#include "sim/record/envelope.h"

namespace metrosync {
namespace {

TEST(OrderParameter, IdenticalPhasesGiveOneAndTheirPhase) {
  const Order o = orderParameter(std::vector<double>(30, 0.7));
  EXPECT_NEAR(o.r, 1.0, 1e-15);
  EXPECT_NEAR(o.Phi, 0.7, 1e-15);
  // two opposite halves cancel
  std::vector<double> half(10, 0.3);
  for (int i = 0; i < 10; ++i) half.push_back(0.3 + kPi);
  EXPECT_NEAR(orderParameter(half).r, 0.0, 1e-15);
}

TEST(OrderParameter, RandomPhasesHaveMeanSquareOneOverN) {
  // E[r^2] = 1/n for n independent uniform phases; n r^2 is ~Exp(1) (sd 1), so the mean of
  // 4000 trials has sd ~0.016: 0.08 is five of them
  std::mt19937 gen(13);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  for (int n : {5, 30, 100}) {
    double sum = 0.0;
    const int trials = 4000;
    for (int t = 0; t < trials; ++t) {
      std::vector<double> ph(n);
      for (double& p : ph) p = u(gen);
      const double r = orderParameter(ph).r;
      sum += n * r * r;
    }
    EXPECT_NEAR(sum / trials, 1.0, 0.08) << "n = " << n;
  }
}

TEST(OrderParameter, PendulumPhaseInvertsTheEnvelope) {
  const double A = 0.6, omega = 20.9;
  for (double phi : {-3.0, -1.2, 0.0, 0.4, 2.9})
    EXPECT_NEAR(pendulumPhase(A * std::sin(phi), A * omega * std::cos(phi), omega), phi, 1e-14);
}

// Groups of metronomes over 50 fast periods (the window: the last 5), every metronome alive
// (A = 1 > theta_c = 0.5) unless `dead(g, i)`: the phases come from `phase(g, i, t)` (unwrapped),
// the groups' order parameters feed the network window and each group's phases its own regime
// window (with the network's platform rules), as NetworkVerdict does; classifyPlatforms judges.
template <class F, class D>
PlatformsVerdict judge(F phase, D dead, const std::vector<int>& sizes, double t_end = 50.0) {
  const double period = 1.0, epsilon = 1.0 / (2 * kPi);  // tau = t
  const int groups = static_cast<int>(sizes.size());
  NetworkWindow w(groups, t_end, period);
  std::vector<RegimeWindow> own(groups, RegimeWindow(t_end, epsilon, networkPlatformRules()));
  for (int k = 0; k <= 1000; ++k) {
    const double t = t_end * k / 1000;
    std::vector<Order> orders;
    for (int g = 0; g < groups; ++g) {
      std::vector<double> ph;
      EnvelopeRow row;
      row.tau = t;
      for (int i = 0; i < sizes[g]; ++i) {
        ph.push_back(phase(g, i, t));
        row.A.push_back(dead(g, i) ? 0.1 : 1.0);
        if (i > 0) row.psi.push_back(ph[0] - ph[i]);
      }
      orders.push_back(orderParameter(ph));
      own[g].add(row);
    }
    w.add(t, orders);
  }
  std::vector<std::vector<double>> theta_c;
  for (int g = 0; g < groups; ++g) theta_c.emplace_back(sizes[g], 0.5);
  return classifyPlatforms(w, own, theta_c);
}

template <class F, class D>
std::string label(F phase, D dead, const std::vector<int>& sizes = {15, 15}) {
  return judge(phase, dead, sizes).label;
}

template <class F>
std::string label(F phase, const std::vector<int>& sizes = {15, 15}) {
  return label(
      phase, [](int, int) { return false; }, sizes);
}

const double w0 = 2 * kPi;
// every metronome at its own frequency, phases spread: no two stay locked over the window
double drifting(int i, double t) {
  return (w0 + 0.7 * i) * t + 2 * kPi * i / 15;
}

TEST(NetworkLabel, EachRuleOnGroupsBuiltForIt) {
  EXPECT_EQ(label([&](int, int i, double t) { return w0 * t + 0.01 * i; }), "synchronized");
  EXPECT_EQ(label([&](int g, int i, double t) { return w0 * t + g * kPi + 0.01 * i; }),
            "antiphase-groups");
  // group 2 incoherent beside a group in phase
  EXPECT_EQ(label([&](int g, int i, double t) { return g == 0 ? w0 * t : drifting(i, t); }),
            "chimera");
  EXPECT_EQ(label([&](int, int i, double t) { return drifting(i, t); }), "disordered");
}

// A single rig is the one-platform case: a network of one platform is named by the
// single-platform rules (SPEC 4), never by the network's (main said synchronized and
// coherent-groups here).
TEST(NetworkLabel, OnePlatformIsNamedAsASingleRig) {
  EXPECT_EQ(label([&](int, int i, double t) { return w0 * t + 0.01 * i; }, {3}), "in-phase");
  EXPECT_EQ(label([&](int, int i, double t) { return w0 * t + i * kPi; }, {2}), "antiphase");
  EXPECT_EQ(label([&](int, int i, double t) { return w0 * t + (i % 2) * kPi; }, {4}),
            "clusters:2+2");
  EXPECT_EQ(label([&](int, int i, double t) { return w0 * t + 0.01 * i; },
                  [](int, int i) { return i == 2; }, {3}),
            "suppressed:1;in-phase");
  EXPECT_EQ(label([&](int, int i, double t) { return drifting(i, t); }, {3}), "drift");
  // two platforms: the network's rules still (the same boards side by side)
  EXPECT_EQ(label([&](int, int i, double t) { return w0 * t + 0.01 * i; }, {3, 3}), "synchronized");
}

// The example: one board's pair in phase, the other's in antiphase, both locked (the
// second board's r is 0). Coherent, so no chimera, whatever r says (main called it `chimera`).
TEST(NetworkLabel, BoardsLockedInPhaseAndInAntiphaseAreNoChimera) {
  const std::vector<int> two_pairs = {2, 2};
  EXPECT_EQ(label([&](int g, int i, double t) { return w0 * t + g * i * kPi; }, two_pairs),
            "coherent-groups");
  // the same with a wobble of 0.1 rad within each period (a locked pair is never exact), and
  // with the boards drifting against each other
  EXPECT_EQ(
      label([&](int g, int i,
                double t) { return (w0 + 0.3 * g) * t + g * i * (kPi + 0.05 * std::sin(w0 * t)); },
            two_pairs),
      "coherent-groups");
  // 15 a side: a group split into two halves in antiphase (r ~ 0.07) is locked, hence coherent
  EXPECT_EQ(label([&](int g, int i, double t) { return w0 * t + g * (i % 2) * kPi; }),
            "coherent-groups");
}

// Coherence is locking, not r: a locked group with r ~ 0 beside a drifting one is a chimera.
TEST(NetworkLabel, ChimeraNeedsAnIncoherentGroupBesideALockedOne) {
  EXPECT_EQ(label([&](int g, int i, double t) {
              return g == 0 ? w0 * t + (i % 2) * kPi : drifting(i, t);
            }),
            "chimera");
  // two pairs: one locked, one whose members drift apart
  EXPECT_EQ(
      label([&](int g, int i, double t) { return g == 0 ? w0 * t : (w0 + 0.9 * i) * t; }, {2, 2}),
      "chimera");
  // a few solitary drifters in a locked majority: not incoherent (13 of 15 locked)
  EXPECT_EQ(
      label([&](int g, int i, double t) { return g == 0 || i < 13 ? w0 * t : drifting(i, t); }),
      "disordered");
  // two drifting clusters of 8 and 7: a locked majority, not incoherent
  EXPECT_EQ(label([&](int g, int i, double t) {
              return g == 0 ? w0 * t : (i < 8 ? w0 * t : (w0 + 0.5) * t);
            }),
            "disordered");
  // ... 7 and 8 of 15, but with one more drifter each side: no cluster above half
  EXPECT_EQ(label([&](int g, int i, double t) {
              return g == 0 ? w0 * t : i < 7 ? w0 * t : i < 14 ? (w0 + 0.5) * t : drifting(i, t);
            }),
            "chimera");
  // frequencies spread evenly: each metronome locked to its neighbours only (0.4 rad over the
  // window), the rest drifting: incoherent, though a chain of locked pairs runs through the group
  EXPECT_EQ(label([&](int g, int i, double t) { return g == 0 ? w0 * t : (w0 + 0.08 * i) * t; }),
            "chimera");
  // a single alive metronome is no synchronous part: the other group drifts, no chimera
  EXPECT_EQ(label([&](int g, int i, double t) { return g == 0 ? w0 * t : drifting(i, t); },
                  [](int g, int i) { return g == 0 && i > 0; }),
            "disordered");
  // dead metronomes take no part: a locked group whose dead ones sit anywhere is coherent
  EXPECT_EQ(label(
                [&](int g, int i, double t) {
                  return g == 0 ? w0 * t + (i > 10 ? 0.3 * i * t : 0.0) : drifting(i, t);
                },
                [](int g, int i) { return g == 0 && i > 10; }),
            "chimera");
}

// Issue 37: a network whose platforms each say `unsettled` was labelled `coherent-groups` (the
// platforms judged settled within 0.1 rad, their groups locked within 0.5 rad, on phases that
// wobble within each period). A platform's verdict and its group's locking now say the same: for
// two boards whose pairs wobble by 0.04 to 3 rad, a platform is settled exactly when its group is
// coherent, and a label of coherent boards never stands beside an unsettled platform.
TEST(NetworkLabel, APlatformsVerdictAgreesWithItsGroupsLocking) {
  auto none = [](int, int) { return false; };
  for (double wobble : {0.02, 0.05, 0.1, 0.2, 0.24, 0.26, 0.4, 0.8, 1.5}) {
    SCOPED_TRACE("wobble " + std::to_string(2 * wobble) + " rad peak to peak");
    auto phase = [&](int g, int i, double t) {
      return w0 * t + i * (g * kPi + wobble * std::sin(3 * t + g));
    };
    const PlatformsVerdict v = judge(phase, none, {2, 2});
    const bool locked = 2 * wobble < NetworkRules::kLocked;
    for (const RegimeVerdict& p : v.platforms) {
      const std::string name = regimeName(p);
      EXPECT_EQ(name == "unsettled" || name == "drift", !locked) << name;
    }
    EXPECT_EQ(v.label == "coherent-groups", locked) << v.label;
  }
}

// A run too short to judge (fewer than 5 fast periods) is `unsettled` as a network, as each of its
// platforms is (main: coherent-groups for a run of 4 periods of boards in phase and in
// antiphase); so is a run with a metronome dying in the window (RegimeVerdict::undecided).
TEST(NetworkLabel, ARunTooShortOrDyingIsUnsettled) {
  auto none = [](int, int) { return false; };
  auto boards = [&](int g, int i, double t) { return w0 * t + g * i * kPi; };
  const PlatformsVerdict short_run = judge(boards, none, {2, 2}, 4.0);
  EXPECT_EQ(short_run.label, "unsettled");
  for (const RegimeVerdict& p : short_run.platforms) EXPECT_TRUE(p.undecided);
  EXPECT_EQ(judge(boards, none, {2, 2}, 50.0).label, "coherent-groups");
}
}  // namespace
}  // namespace metrosync
