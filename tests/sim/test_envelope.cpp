#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "base/constants.h"
#include "sim/record/envelope.h"
#include "sim/record/envelope_recorder.h"

namespace metrosync {
namespace {

// an angle difference moved into (-pi, pi]
double wrapPsi(double d) {
  return std::remainder(d, 2 * kPi);
}

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

// ---- EnvelopeRecorder: the start's row, the period rows, the final row
// ---------------------------

namespace metrosync {
namespace {

// A slowly modulated oscillation with a closed-form envelope: theta = A(t) sin(t + phi(t)),
// thetadot = A(t) cos(t + phi(t)), A and phi linear in t, so A = hypot(theta, thetadot) and
// atan2(theta, thetadot) - t = phi exactly. Over any interval [a, b] the average of A is A at the
// midpoint, and the average of exp(i phi) points along phi at the midpoint (a real sinc factor).
struct Modulated {
  double A0, dA, phi0, dphi;
  double A(double t) const { return A0 + dA * t; }
  double phi(double t) const { return phi0 + dphi * t; }
};

struct Recording {
  MemorySink sink;
  EnvelopeRow final_row;
  double span = 0.0;
};

// Two metronomes sampled like an engine does (64 samples per period, one at t_end), then finish().
Recording record(const Modulated& m1, const Modulated& m2, double eps, double t_end) {
  Recording r;
  EnvelopeRecorder rec(eps, {true, true}, r.sink);
  auto sampleAt = [&](double t) {
    const double th[2] = {m1.A(t) * std::sin(t + m1.phi(t)), m2.A(t) * std::sin(t + m2.phi(t))};
    const double w[2] = {m1.A(t) * std::cos(t + m1.phi(t)), m2.A(t) * std::cos(t + m2.phi(t))};
    rec.sample(t, th, w);
  };
  const double dt = kTwoPi / 64;
  for (long k = 0; k * dt < t_end; ++k) sampleAt(k * dt);
  sampleAt(t_end);
  r.final_row = rec.finish();
  r.span = rec.finalSpan();
  return r;
}

TEST(EnvelopeRecorder, FirstRowIsTheStartsEnvelopeAndLastIsTheFinalPeriodEndingAtTEnd) {
  const Modulated m1{1.9, 0.004, 0.3, 0.01}, m2{1.7, -0.003, 2.9, -0.02};
  const double eps = 0.05, t_end = kTwoPi * 7.37;  // ends inside a period
  const Recording r = record(m1, m2, eps, t_end);
  const auto& rows = r.sink.envelope;
  ASSERT_EQ(rows.size(), 1u + 7u + 1u);  // start, 7 complete periods, final
  // the start: the instantaneous envelope at t = 0, exactly
  EXPECT_EQ(rows.front().tau, 0.0);
  EXPECT_NEAR(rows.front().A[0], 1.9, 1e-15);
  EXPECT_NEAR(rows.front().A[1], 1.7, 1e-15);
  EXPECT_NEAR(rows.front().psi[0], 0.3 - 2.9 + 2 * kPi, 1e-14);  // first value put in [0, 2 pi)
  // the period rows stay on the shared grid
  for (long k = 0; k < 7; ++k) EXPECT_EQ(rows[k + 1].tau, envelopeTau(eps, k));
  // the final row: tau_end, and the average over [t_end - 2 pi, t_end]: A and phi at its middle.
  // The trapezoid rule on 64 samples per period, the window's start interpolated linearly:
  // errors ~ (2 pi / 64)^2 dphi^2 ~ 1e-6 relative at most; 1e-6 absolute.
  EXPECT_EQ(rows.back().tau, eps * t_end);
  EXPECT_EQ(r.final_row.tau, rows.back().tau);
  EXPECT_EQ(r.span, kTwoPi);
  const double mid = t_end - kPi;
  EXPECT_NEAR(r.final_row.A[0], m1.A(mid), 1e-6);
  EXPECT_NEAR(r.final_row.A[1], m2.A(mid), 1e-6);
  EXPECT_NEAR(wrapPsi(r.final_row.psi[0] - (m1.phi(mid) - m2.phi(mid))), 0.0, 1e-6);
  // and not the last period row's values (a different period): the test can tell them apart
  EXPECT_GT(std::fabs(r.final_row.A[0] - rows[rows.size() - 2].A[0]), 1e-3);
}

TEST(EnvelopeRecorder, ARunShorterThanAPeriodIsAveragedOverWhatThereIs) {
  const Modulated m1{1.9, 0.05, 0.3, 0.02}, m2{1.7, 0.0, 1.0, 0.0};
  const double eps = 0.05, t_end = 2.0;
  const Recording r = record(m1, m2, eps, t_end);
  ASSERT_EQ(r.sink.envelope.size(), 2u);  // the start and the final row, no complete period
  EXPECT_EQ(r.span, t_end);
  EXPECT_EQ(r.final_row.tau, eps * t_end);
  EXPECT_NEAR(r.final_row.A[0], m1.A(1.0), 1e-6);
  EXPECT_NEAR(wrapPsi(r.final_row.psi[0] - (m1.phi(1.0) - m2.phi(1.0))), 0.0, 1e-6);
}

TEST(EnvelopeRecorder, ARunEndingOnABoundaryRepeatsTheLastPeriodAtTauEnd) {
  const Modulated m1{1.9, 0.004, 0.3, 0.01}, m2{1.7, -0.003, 2.9, -0.02};
  const double eps = 0.05, t_end = kTwoPi * 3;
  const Recording r = record(m1, m2, eps, t_end);
  const auto& rows = r.sink.envelope;
  ASSERT_EQ(rows.size(), 1u + 3u + 1u);
  const EnvelopeRow &period = rows[3], &fin = rows[4];
  EXPECT_EQ(fin.tau, eps * t_end);
  EXPECT_NEAR(fin.A[0], period.A[0], 1e-13);
  EXPECT_NEAR(fin.A[1], period.A[1], 1e-13);
  EXPECT_NEAR(fin.psi[0], period.psi[0], 1e-13);
}

}  // namespace
}  // namespace metrosync
