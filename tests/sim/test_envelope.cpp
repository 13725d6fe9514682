#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "sim/record/envelope.h"

namespace metrosync {
namespace {

constexpr double kPi = 3.141592653589793;

TEST(PhaseUnwrapper, FirstValueLandsInZeroToTwoPi) {
  PhaseUnwrapper u;
  EXPECT_NEAR(u(-0.5), 2 * kPi - 0.5, 1e-15);
  PhaseUnwrapper v;
  EXPECT_NEAR(v(7.0), 7.0 - 2 * kPi, 1e-15);
}

TEST(PhaseUnwrapper, FollowsAPhaseThroughManyTurns) {
  // a phase that grows by 0.3 rad per sample, fed in wrapped to (-pi, pi]
  PhaseUnwrapper u;
  const double start = 0.2;
  for (int k = 0; k < 200; ++k) {
    const double truth = start + 0.3 * k;
    const double wrapped = std::atan2(std::sin(truth), std::cos(truth));
    EXPECT_NEAR(u(wrapped), truth, 1e-12) << "sample " << k;
  }
}

TEST(EnvelopeCsv, RoundTripsRows) {
  EnvelopeRow r{0.25, {1.5, 2.25, 0.125}, {3.0, -0.5}};
  const std::string path = ::testing::TempDir() + "/env_roundtrip.csv";
  {
    std::ofstream out(path);
    out << envelopeHeader(3) << "\n" << formatEnvelopeRow(r) << "\n";
  }
  auto rows = readEnvelopeCsv(path);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_DOUBLE_EQ(rows[0].tau, 0.25);
  ASSERT_EQ(rows[0].A.size(), 3u);
  ASSERT_EQ(rows[0].psi.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0].A[1], 2.25);
  EXPECT_DOUBLE_EQ(rows[0].psi[1], -0.5);
  EXPECT_EQ(envelopeHeader(3), "tau,A_1,A_2,A_3,psi_2,psi_3,r");
}

}  // namespace
}  // namespace metrosync
