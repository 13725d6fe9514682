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

// Two groups of 15 over 10 periods: group phases from `phase(g, i, t)`.
template <class F>
std::string label(F phase) {
  const double period = 1.0, t_end = 50.0;
  NetworkWindow w(2, t_end, period);
  for (int k = 0; k <= 1000; ++k) {
    const double t = t_end * k / 1000;
    std::vector<Order> groups;
    for (int g = 0; g < 2; ++g) {
      std::vector<double> ph;
      for (int i = 0; i < 15; ++i) ph.push_back(phase(g, i, t));
      groups.push_back(orderParameter(ph));
    }
    w.add(t, groups);
  }
  return classifyNetwork(w);
}

TEST(NetworkLabel, EachRuleOnGroupsBuiltForIt) {
  const double w0 = 2 * kPi;
  EXPECT_EQ(label([&](int, int i, double t) { return w0 * t + 0.01 * i; }), "synchronized");
  EXPECT_EQ(label([&](int g, int i, double t) { return w0 * t + g * kPi + 0.01 * i; }),
            "antiphase-groups");
  // group 2: every metronome at its own frequency (spread phases, drifting)
  EXPECT_EQ(label([&](int g, int i, double t) {
              return g == 0 ? w0 * t : (w0 + 0.7 * i) * t + 2 * kPi * i / 15;
            }),
            "chimera");
  EXPECT_EQ(label([&](int, int i, double t) { return (w0 + 0.7 * i) * t + 2 * kPi * i / 15; }),
            "disordered");
}

}  // namespace
}  // namespace metrosync
