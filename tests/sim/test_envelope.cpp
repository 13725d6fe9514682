#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "base/constants.h"
#include "sim/record/envelope.h"
#include "sim/record/envelope_csv.h"
#include "sim/record/envelope_quadrature.h"

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

// ---- EnvelopeQuadrature: the start's row, the period rows, the final row
// ---------------------------

namespace metrosync {
namespace {

// A slowly modulated oscillation with a closed-form envelope: theta = A(t) sin(t + phi(t)),
// thetadot = A(t) cos(t + phi(t)), A and phi linear in t, so A = hypot(theta, thetadot) and
// atan2(theta, thetadot) - t = phi exactly. Over any interval [a, b] the average of A is A at the
// midpoint, and the average of exp(i phi) points along phi at the midpoint (a real sinc factor).
// `jump` adds a step to A at t_jump (an impulse): the stretches must end there.
struct Modulated {
  double A0, dA, phi0, dphi, t_jump = 1e300, jump = 0.0;
  double A(double t) const { return A0 + dA * t + (t >= t_jump ? jump : 0.0); }
  double phi(double t) const { return phi0 + dphi * t; }
  // the exact average of A over [a, b] (b > a)
  double meanA(double a, double b) const {
    const double in_jump = std::max(0.0, b - std::max(a, t_jump));
    return A0 + dA * 0.5 * (a + b) + jump * in_jump / (b - a);
  }
};

struct Recording {
  MemorySink sink;
  EnvelopeRow final_row;
  double span = 0.0;
};

// Two metronomes handed over as an engine does, in stretches of uneven lengths that end at every
// jump, then finish(); `stop`: where the run stopped (t_end for a complete run).
Recording record(const Modulated& m1, const Modulated& m2, double eps, double t_end,
                 double stop = -1.0) {
  Recording r;
  if (stop < 0) stop = t_end;
  EnvelopeQuadrature q(eps, {true, true}, t_end, r.sink);
  // (the Gauss nodes lie inside a stretch: a stretch ending at a jump never sees its far side)
  auto state = [&](double t, double* th, double* w) {
    const double a1 = m1.A(t), a2 = m2.A(t);
    th[0] = a1 * std::sin(t + m1.phi(t));
    th[1] = a2 * std::sin(t + m2.phi(t));
    w[0] = a1 * std::cos(t + m1.phi(t));
    w[1] = a2 * std::cos(t + m2.phi(t));
  };
  double th[2], w[2];
  state(0.0, th, w);
  q.start(th, w);
  const double steps[] = {0.31, 0.77, 0.05, 0.52, 0.9};  // scaled-time step sizes, in turn
  double t = 0.0;
  for (int k = 0; t < stop; ++k) {
    double next = std::min(stop, t + steps[k % 5]);
    for (double tj : {m1.t_jump, m2.t_jump})
      if (tj > t && tj < next) next = tj;
    q.stretchAt(t, next, state);
    t = next;
  }
  r.final_row = q.finish();
  r.span = q.finalSpan();
  return r;
}

TEST(EnvelopeQuadrature, FirstRowIsTheStartsEnvelopeAndLastIsTheFinalPeriodEndingAtTEnd) {
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
  // the period rows stay on the shared grid, each the exact average of its period: the Gauss
  // rule on pieces of at most 0.9 of a smooth integrand errs by ~1e-16 (dphi^8 h^9 terms)
  for (long k = 0; k < 7; ++k) {
    EXPECT_EQ(rows[k + 1].tau, envelopeTau(eps, k));
    const double mid = kTwoPi * (k + 0.5);
    EXPECT_NEAR(rows[k + 1].A[0], m1.A(mid), 1e-13) << k;
    EXPECT_NEAR(rows[k + 1].A[1], m2.A(mid), 1e-13) << k;
    EXPECT_NEAR(wrapPsi(rows[k + 1].psi[0] - (m1.phi(mid) - m2.phi(mid))), 0.0, 1e-13) << k;
  }
  // the final row: tau_end, and the average over [t_end - 2 pi, t_end]
  EXPECT_EQ(rows.back().tau, eps * t_end);
  EXPECT_EQ(r.final_row.tau, rows.back().tau);
  EXPECT_NEAR(r.span, kTwoPi, 1e-13);
  const double mid = t_end - kPi;
  EXPECT_NEAR(r.final_row.A[0], m1.A(mid), 1e-13);
  EXPECT_NEAR(r.final_row.A[1], m2.A(mid), 1e-13);
  EXPECT_NEAR(wrapPsi(r.final_row.psi[0] - (m1.phi(mid) - m2.phi(mid))), 0.0, 1e-13);
  // and not the last period row's values (a different period): the test can tell them apart
  EXPECT_GT(std::fabs(r.final_row.A[0] - rows[rows.size() - 2].A[0]), 1e-3);
}

// An impulse inside a period: the stretch ends at it, and the period's average is the exact
// average of a step function (a trapezoid over 64 samples per period errs by ~jump / 128 here).
TEST(EnvelopeQuadrature, AJumpInsideAPeriodIsAveragedExactly) {
  Modulated m1{1.9, 0.004, 0.3, 0.01}, m2{1.7, -0.003, 2.9, -0.02};
  m1.t_jump = kTwoPi * 2.3137;
  m1.jump = 0.25;
  const double eps = 0.05, t_end = kTwoPi * 4.5;
  const Recording r = record(m1, m2, eps, t_end);
  const auto& rows = r.sink.envelope;
  ASSERT_EQ(rows.size(), 1u + 4u + 1u);
  for (long k = 0; k < 4; ++k)
    EXPECT_NEAR(rows[k + 1].A[0], m1.meanA(kTwoPi * k, kTwoPi * (k + 1)), 1e-13) << k;
  EXPECT_NEAR(r.final_row.A[0], m1.meanA(t_end - kTwoPi, t_end), 1e-13);
}

TEST(EnvelopeQuadrature, ARunShorterThanAPeriodIsAveragedOverWhatThereIs) {
  const Modulated m1{1.9, 0.05, 0.3, 0.02}, m2{1.7, 0.0, 1.0, 0.0};
  const double eps = 0.05, t_end = 2.0;
  const Recording r = record(m1, m2, eps, t_end);
  ASSERT_EQ(r.sink.envelope.size(), 2u);  // the start and the final row, no complete period
  EXPECT_EQ(r.span, t_end);
  EXPECT_EQ(r.final_row.tau, eps * t_end);
  EXPECT_NEAR(r.final_row.A[0], m1.A(1.0), 1e-13);
  EXPECT_NEAR(wrapPsi(r.final_row.psi[0] - (m1.phi(1.0) - m2.phi(1.0))), 0.0, 1e-13);
}

TEST(EnvelopeQuadrature, ARunEndingOnABoundaryRepeatsTheLastPeriodAtTauEnd) {
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

// A run that stopped before its planned end: the final row averages the pieces of its last 2 pi
// (those that start within it), and says how long that was.
TEST(EnvelopeQuadrature, AStoppedRunAveragesItsLastPieces) {
  const Modulated m1{1.9, 0.004, 0.3, 0.01}, m2{1.7, -0.003, 2.9, -0.02};
  const double eps = 0.05, t_end = kTwoPi * 9, stop = kTwoPi * 5.61;
  const Recording r = record(m1, m2, eps, t_end, stop);
  EXPECT_EQ(r.final_row.tau, eps * stop);
  EXPECT_LE(r.span, kTwoPi);
  EXPECT_GT(r.span, kTwoPi - 0.9);  // the pieces are at most 0.9 long
  const double mid = stop - 0.5 * r.span;
  EXPECT_NEAR(r.final_row.A[0], m1.A(mid), 1e-13);
  EXPECT_NEAR(r.final_row.A[1], m2.A(mid), 1e-13);
}

}  // namespace
}  // namespace metrosync
