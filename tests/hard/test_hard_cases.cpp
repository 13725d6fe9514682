// The hard cases of the full model (yaml/rigs/hard/), on the direct engine: each must end with a
// finite state, a closed energy ledger, event counts consistent with the event rows and with
// each other across tolerances, and whatever exact property the case has (a closed form, a
// symmetry, an equivalent rig). tests/direct/test_agreement.cpp compares the two engines on the
// same rigs.
//
// Tolerances used throughout:
//   ledger: relative residual <= 1e-6 (the bound; the quadratures run at the integrator's
//     accuracy, 1e-8 by default, and measured residuals are 1e-12..1e-8);
//   across tolerances: a run at the default accuracy 1e-8 against one at 1e-11; their envelopes
//     may differ by the default run's global error, measured <= 2e-7 over 650 periods of the
//     default rig: 1e-5 leaves a factor 50 for rigs that are harder or longer.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>

#include "base/constants.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

const std::string kHard = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/hard/";

Rig hardRig(const std::string& name, std::vector<std::string> sets = {}) {
  return loadRigFile(kHard + name, sets);
}

struct HardRun {
  RunReport report;
  MemorySink sink;
  long tickRows() const { return countRows("tick"); }
  long switchRows() const {
    // stick/slip rows after the start (a platform that breaks free at t = 0 writes a row, but the
    // start is not a switch)
    long n = 0;
    for (const auto& [kind, row] : sink.events)
      if ((kind == "stick" || kind == "slip") && row[0] > 0) ++n;
    return n;
  }
  long countRows(const std::string& kind) const {
    long n = 0;
    for (const auto& e : sink.events) n += e.first == kind;
    return n;
  }
};

HardRun runDirect(Rig rig, double accuracy = 0.0) {
  if (accuracy > 0) rig.sim.accuracy = accuracy;
  HardRun r;
  r.report = runDirectModel(rig, r.sink);
  return r;
}

// What every hard case must satisfy.
void expectSound(const HardRun& r, const std::string& what) {
  ASSERT_TRUE(r.report.complete) << what << ": " << r.report.failure;
  for (double v : r.report.final_trajectory_row) ASSERT_TRUE(std::isfinite(v)) << what;
  ASSERT_TRUE(r.report.has_ledger);
  EXPECT_LE(std::abs(r.report.ledger.relativeResidual()), 1e-6)
      << what << ": ledger residual " << r.report.ledger.residual_J() << " J";
  // every switch (stick <-> slip, or a slip reversal) is counted once and written once; every
  // tick window writes one row and ticks at least one metronome; an event window holds at least a
  // tick or a switch
  const long switches = r.report.counts.stick_slip + r.report.counts.slip_reversals;
  EXPECT_EQ(switches, r.switchRows()) << what;
  long ticks = 0;
  for (long e : r.report.counts.escapements) ticks += e;
  EXPECT_GE(ticks, r.tickRows()) << what;
  EXPECT_LE(ticks, r.tickRows() * static_cast<long>(r.report.counts.escapements.size())) << what;
  EXPECT_GE(r.report.counts.events, r.tickRows()) << what;
  EXPECT_LE(r.report.counts.events, r.tickRows() + switches) << what;
}

double maxEnvelopeDifference(const HardRun& a, const HardRun& b) {
  EXPECT_EQ(a.sink.envelope.size(), b.sink.envelope.size());
  double worst = 0;
  for (size_t k = 0; k < std::min(a.sink.envelope.size(), b.sink.envelope.size()); ++k) {
    const EnvelopeRow &ra = a.sink.envelope[k], &rb = b.sink.envelope[k];
    for (size_t i = 0; i < ra.A.size(); ++i) worst = std::max(worst, std::abs(ra.A[i] - rb.A[i]));
    for (size_t j = 0; j < ra.psi.size(); ++j)
      worst = std::max(worst, std::abs(ra.psi[j] - rb.psi[j]));
  }
  return worst;
}

// --- grazing ---------------------------------------------------------------------------------

// Fixed platform, so each metronome is alone and its fate follows from its energy: an undamped
// pendulum started at the bottom with thetadot0 tops out where (1 - cos(sqrt(eps) theta_max)) /
// eps = thetadot0^2 / 2 (see the rig's comments for the numbers).
TEST(HardCases, GrazingTicksAreNeitherMissedNorInvented) {
  const HardRun loose = runDirect(hardRig("grazing.yaml"));
  const HardRun tight = runDirect(hardRig("grazing.yaml"), 1e-11);
  expectSound(loose, "grazing @1e-8");
  expectSound(tight, "grazing @1e-11");
  const auto& e = loose.report.counts.escapements;
  EXPECT_EQ(e, tight.report.counts.escapements);
  EXPECT_EQ(e[0], 0) << "at rest exactly at theta_c: a turning point, not a crossing";
  EXPECT_EQ(e[1], 0) << "amplitude theta_c at the bottom, damped: never reaches theta_c";
  EXPECT_GE(e[2], 1) << "tops out 1e-7 above theta_c: the graze must tick";
  EXPECT_EQ(e[3], 0) << "tops out 1e-7 below theta_c: no tick";
  EXPECT_GT(e[4], 0) << "the dying metronome ticks while its amplitude is above theta_c";
  // ... and then dies: its final amplitude is below theta_c (its last ticks were grazing)
  const ScaledParams sp = computeScaled(hardRig("grazing.yaml"));
  EXPECT_LT(loose.report.final_row.A[4], sp.theta_c[4]);
  EXPECT_LT(maxEnvelopeDifference(loose, tight), 1e-5);
}

// --- the drive at the two thresholds of beta1, beta2 ------------------------------------------

// Windows holding a tick (the pair ticks together: one window, two ticks).
long tickWindows(const HardRun& r) {
  return r.tickRows();
}

TEST(HardCases, DriveAtTheStickThresholdBreaksFreeAtATangencyWithoutChattering) {
  const HardRun a = runDirect(hardRig("drive-s1.yaml"));
  const HardRun b = runDirect(hardRig("drive-s1.yaml"), 1e-11);
  expectSound(a, "drive-s1 @1e-8");
  expectSound(b, "drive-s1 @1e-11");
  // every tick on the stuck platform is a slip and a stick; the threshold adds a few slips of
  // the push's own (more than none: the case is at the threshold; far fewer than two per period,
  // which is what a platform clearly above the threshold would do)
  const long from_ticks = 2 * tickWindows(a);
  const long periods = std::lround(a.report.final_row.tau / (0.02 * 2 * kPi));
  EXPECT_GT(a.report.counts.stick_slip, from_ticks);
  EXPECT_LT(a.report.counts.stick_slip, from_ticks + periods);
  // the same switches at both tolerances (a tangency decided by integration noise would not be)
  EXPECT_EQ(a.report.counts.stick_slip, b.report.counts.stick_slip);
  EXPECT_EQ(a.report.counts.escapements, b.report.counts.escapements);
  EXPECT_LT(maxEnvelopeDifference(a, b), 1e-5);
}

TEST(HardCases, DriveAtThePureSlipThresholdStopsForAnInstantOrNotAtAll) {
  const HardRun a = runDirect(hardRig("drive-pure-slip.yaml"));
  const HardRun b = runDirect(hardRig("drive-pure-slip.yaml"), 1e-11);
  expectSound(a, "drive-pure-slip @1e-8");
  expectSound(b, "drive-pure-slip @1e-11");
  // two reversals per period; at some the platform sticks for an instant, at most it does not
  const long sticks = a.countRows("stick"), slips = a.countRows("slip");
  const long periods = std::lround(a.report.final_row.tau / (0.02 * 2 * kPi));
  EXPECT_GT(sticks, 0);
  EXPECT_LT(sticks, periods);
  EXPECT_NEAR(static_cast<double>(slips), 2.0 * periods, 4.0);
  EXPECT_EQ(a.report.counts.stick_slip, b.report.counts.stick_slip);
  EXPECT_EQ(a.countRows("stick"), b.countRows("stick"));
  EXPECT_LT(maxEnvelopeDifference(a, b), 1e-5);
}

// --- symmetric starts -------------------------------------------------------------------------

TEST(HardCases, IdenticalMetronomesInPhaseTickTogetherAndEqualOneDoubledMetronome) {
  Rig pair = hardRig("inphase-identical.yaml");
  pair.units = Units::Physical;  // compare in SI: the doubled rig has other scaled units
  const HardRun r2 = runDirect(pair, 1e-11);
  expectSound(r2, "in phase");
  EXPECT_EQ(r2.report.counts.escapements[0], r2.report.counts.escapements[1]);
  EXPECT_GT(r2.report.counts.escapements[0], 50);
  // every tick window ticks both: as many windows as ticks of one
  EXPECT_EQ(r2.tickRows(), r2.report.counts.escapements[0]);
  // the pair stays identical to the last bit (same arithmetic on the same numbers)
  for (const auto& row : r2.sink.trajectory) {
    ASSERT_EQ(row[3], row[5]) << "t = " << row[0];
    ASSERT_EQ(row[4], row[6]) << "t = " << row[0];
  }
  // e1.1a-c: the pair is one metronome with twice the mass, inertia, damping and impulse
  Rig one = pair;
  one.metronomes.resize(1);
  MetronomeSpec& m = one.metronomes[0];
  m.box_mass_kg *= 2;
  m.pendulum_mass_kg *= 2;
  m.inertia_kgm2 *= 2;
  m.damping_kg_s *= 2;
  m.impulse_Nms *= 2;
  const HardRun r1 = runDirect(one, 1e-11);
  expectSound(r1, "doubled");
  EXPECT_EQ(r1.report.counts.escapements[0], r2.report.counts.escapements[0]);
  EXPECT_EQ(r1.report.counts.stick_slip, r2.report.counts.stick_slip);
  ASSERT_EQ(r1.sink.trajectory.size(), r2.sink.trajectory.size());
  // two integrations of the same equations at 1e-11, but not with the same steps: the reference
  // metronome (metronome 1) differs, hence the scaled units that weigh the error control; they
  // differ by their global errors, ~1e-11 per step over ~1e4 steps (rad, rad/s / 20; x weighted
  // to radian size)
  double worst = 0;
  for (size_t k = 0; k < r1.sink.trajectory.size(); ++k) {
    const auto &a = r1.sink.trajectory[k], &b = r2.sink.trajectory[k];
    worst = std::max(
        {worst, std::abs(a[3] - b[3]), std::abs(a[4] - b[4]) / 20, 1e3 * std::abs(a[1] - b[1])});
  }
  EXPECT_LT(worst, 1e-7);
}

TEST(HardCases, ExactAntiphaseKeepsThePlatformStuckForEver) {
  const HardRun r = runDirect(hardRig("antiphase-exact.yaml"));
  expectSound(r, "antiphase");
  EXPECT_EQ(r.report.counts.stick_slip, 0);
  EXPECT_GT(r.report.counts.escapements[0], 50);
  EXPECT_EQ(r.report.counts.escapements[0], r.report.counts.escapements[1]);
  EXPECT_EQ(r.report.ledger.friction_out_J, 0.0);
  // the forces and the tick impulses cancel exactly: not a bit of motion, mirror images for ever
  for (const auto& row : r.sink.trajectory) {
    ASSERT_EQ(row[1], 0.0) << "t = " << row[0];
    ASSERT_EQ(row[2], 0.0) << "t = " << row[0];
    ASSERT_EQ(row.back(), 0.0) << "t = " << row[0];
    ASSERT_EQ(row[3], -row[5]) << "t = " << row[0];
    ASSERT_EQ(row[4], -row[6]) << "t = " << row[0];
  }
}

// --- the friction coefficient at its extremes -------------------------------------------------

// mu = 0: the platform can never stick, so the motion is the free platform's (law: none); the
// horizontal momentum M xdot + sum_i m_i L_i cos(theta_i) thetadot_i is conserved.
TEST(HardCases, ZeroFrictionIsAFreePlatform) {
  Rig coulomb = hardRig("mu-zero.yaml");
  coulomb.units = Units::Physical;
  Rig none = coulomb;
  none.platform.friction = FrictionLaw::none();
  const HardRun a = runDirect(coulomb, 1e-11), b = runDirect(none, 1e-11);
  expectSound(a, "mu = 0");
  expectSound(b, "law none");
  // it never sticks: every stop is a reversal (stop, settle, break free at once the other way)
  EXPECT_EQ(a.report.counts.stick_slip, 0);
  EXPECT_GT(a.report.counts.slip_reversals, 10);
  EXPECT_EQ(a.countRows("stick"), 0);
  EXPECT_EQ(a.report.counts.escapements, b.report.counts.escapements);
  ASSERT_EQ(a.sink.trajectory.size(), b.sink.trajectory.size());
  const double M = coulomb.totalMass();
  auto momentum = [&](const std::vector<double>& row) {
    double p = M * row[2];
    for (size_t i = 0; i < coulomb.metronomes.size(); ++i) {
      const MetronomeSpec& m = coulomb.metronomes[i];
      p += m.pendulum_mass_kg * m.length_m * std::cos(row[3 + 2 * i]) * row[4 + 2 * i];
    }
    return p;
  };
  const double p0 = momentum(a.sink.trajectory.front());
  const double p_scale = coulomb.metronomes[0].pendulum_mass_kg * coulomb.metronomes[0].length_m *
                         std::abs(a.sink.trajectory.front()[4]);
  double worst_state = 0, worst_p = 0;
  for (size_t k = 0; k < a.sink.trajectory.size(); ++k) {
    const auto &ra = a.sink.trajectory[k], &rb = b.sink.trajectory[k];
    for (size_t c = 3; c + 1 < ra.size(); ++c)
      worst_state = std::max(worst_state, std::abs(ra[c] - rb[c]));
    worst_p = std::max(worst_p, std::abs(momentum(ra) - p0));
  }
  // the same equations, except that the Coulomb run restarts the integrator at every reversal:
  // both at 1e-11, ~1e-9 apart after ~80 periods (rad, rad/s in SI)
  EXPECT_LT(worst_state, 1e-7);
  // momentum: integration error only (tick impulses are internal, friction is zero)
  EXPECT_LT(worst_p, 1e-8 * p_scale);
}

TEST(HardCases, HugeFrictionOnlyLetsTicksMoveThePlatform) {
  const HardRun r = runDirect(hardRig("mu-huge.yaml"));
  expectSound(r, "mu = 1e6");
  // each tick sets the platform moving at dv ~ eps J, which friction stops within
  // dv / (mu * mobility) ~ 1e-7 fast periods: a plastic stop in the same window (the pendulums
  // take the reaction), counted by where it ends, stuck as before: no switch, no slip row
  EXPECT_GT(r.tickRows(), 100);
  EXPECT_EQ(r.report.counts.stick_slip, 0);
  EXPECT_EQ(r.countRows("slip"), 0);
  EXPECT_EQ(r.countRows("stick"), 0);
  // ... and friction took the kinetic energy of every stop
  EXPECT_GT(r.report.ledger.friction_out_J, 0.0);
  // the platform never moves (a slip integrated for 1e-7 periods would move it by ~1e-9)
  for (const auto& row : r.sink.trajectory) ASSERT_LT(std::abs(row[1]), 1e-6) << "t = " << row[0];
}

// --- long run, many metronomes ----------------------------------------------------------------

TEST(HardCases, SmallEpsilonLongRunIsStableAcrossTolerances) {
  const HardRun a = runDirect(hardRig("eps-small.yaml"));
  const HardRun b = runDirect(hardRig("eps-small.yaml"), 1e-10);
  expectSound(a, "eps 0.001 @1e-8");
  expectSound(b, "eps 0.001 @1e-10");
  EXPECT_GT(a.report.counts.escapements[0], 5000);
  EXPECT_LT(maxEnvelopeDifference(a, b), 1e-5);
  // counts may differ by a tick at the very end (the two runs end a hair apart in phase)
  for (size_t i = 0; i < 2; ++i)
    EXPECT_NEAR(a.report.counts.escapements[i], b.report.counts.escapements[i], 1);
}

TEST(HardCases, HundredMetronomes) {
  const HardRun a = runDirect(hardRig("n100.yaml"));
  const HardRun b = runDirect(hardRig("n100.yaml"), 1e-10);
  expectSound(a, "N = 100 @1e-8");
  expectSound(b, "N = 100 @1e-10");
  EXPECT_EQ(a.report.counts.escapements, b.report.counts.escapements);
  EXPECT_LT(maxEnvelopeDifference(a, b), 1e-5);
}

// --- creeping ---------------------------------------------------------------------------------

// Closed form: the platform (metronomes locked, so a mass M on a spring k with Coulomb friction)
// starts at rest at x0 = x_eq (1 + delta), x_eq = bound / k; it oscillates about x_eq, stops after
// half a period T/2 = pi sqrt(M / k) at x_eq (1 - delta), where friction holds it for good.
void expectCreep(const std::string& file, double delta, double t_tol) {
  const Rig rig = hardRig(file);
  const auto wall0 = std::chrono::steady_clock::now();
  const HardRun r = runDirect(rig);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  expectSound(r, file);
  EXPECT_LT(wall, 2.0) << "creeping must not stall the integrator";
  const double M = rig.totalMass(), k = rig.platform.spring_N_m;
  const double bound = rig.platform.friction.valueOr("mu", 0.0) * M * rig.gravity_m_s2;
  const double x_eq = bound / k;
  ASSERT_NEAR(rig.platform.start_x_m, x_eq * (1 + delta), 1e-3 * delta * x_eq);
  EXPECT_EQ(r.report.counts.stick_slip, 1) << "one stop, and stuck for good";
  ASSERT_EQ(r.countRows("stick"), 1);
  for (const auto& [kind, row] : r.sink.events) {
    if (kind != "stick") continue;
    EXPECT_NEAR(row[0], kPi * std::sqrt(M / k), t_tol) << file;
  }
  // the creep covers 2 delta x_eq; it must end where the closed form says, to 1e-3 of that (but
  // no better than the integrator's absolute error on x, ~1e-8 of x's scale, 4.5e-12 m)
  const double x_end = r.report.final_trajectory_row[1];
  EXPECT_NEAR(x_end, x_eq * (1 - delta), std::max(2e-3 * delta * x_eq, 1e-11)) << file;
  EXPECT_EQ(r.report.final_trajectory_row.back(), 0.0) << "stuck at the end";
}

// The stop is located to the integrator's accuracy: 1e-8 of the time scale (~5e-3 s) and of the
// creep's own speed scale, measured 2e-12 s off.
TEST(HardCases, CreepingPlatformStopsOnceAndForGood) {
  expectCreep("creep.yaml", 1e-6, 1e-7);
}

// Stopping inside the break-free band (margin 1e-10 of the bound < kBreakFreeTol): a slip cannot
// start there, so the platform must stick, not break free, slip backwards and stop again forever.
// Here the creep speed (5e-13 m/s) is far below the error control's absolute floor on xdot (1e-8
// of the velocity scale, 1e-10 m/s), so only the largest step (1/10 of the spring period) limits
// the steps, where the default integrator errs by ~1e-6 relative per step (measured: the stop
// 3e-7 s late): 1e-4 s.
TEST(HardCases, CreepEndingInsideTheBreakFreeBandSticks) {
  expectCreep("creep-band.yaml", 1e-10, 1e-4);
}

// --- event storm ------------------------------------------------------------------------------

TEST(HardCases, EventStormEndsTheRunWithAMessage) {
  const auto wall0 = std::chrono::steady_clock::now();
  const HardRun r = runDirect(hardRig("storm.yaml"));
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  EXPECT_FALSE(r.report.complete);
  EXPECT_NE(r.report.failure.find("event storm"), std::string::npos) << r.report.failure;
  EXPECT_LT(wall, 5.0);
  for (double v : r.report.final_trajectory_row) EXPECT_TRUE(std::isfinite(v));
  // the rows written so far are kept: the start, then what came before the storm
  EXPECT_GE(r.sink.trajectory.size(), 2u);
}

// A state that is not a number (possible only through the library API: the rig loader rejects
// it) ends the run with complete = false and the reason, not a hang or an exception.
TEST(HardCases, NonFiniteStateEndsTheRun) {
  Rig rig = defaultRig();
  rig.metronomes[1].start_rate_rad_s = std::nan("");
  MemorySink sink;
  const RunReport r = runDirectModel(rig, sink);
  EXPECT_FALSE(r.complete);
  EXPECT_NE(r.failure.find("non-finite"), std::string::npos) << r.failure;
}

// The guard itself, forced: a storm threshold of 5 events within a whole run stops the default rig
// at its 6th event (so the threshold is what decides, not an accident of this rig).
TEST(HardCases, StormGuardStopsAtItsThreshold) {
  DirectOptions opt;
  opt.storm_events = 5;
  opt.storm_window = 1e9;  // periods: the whole run is one burst
  MemorySink sink;
  const RunReport r = runDirectModel(defaultRig(), sink, opt);
  EXPECT_FALSE(r.complete);
  EXPECT_NE(r.failure.find("event storm"), std::string::npos) << r.failure;
  EXPECT_EQ(r.counts.events, 6);
}

}  // namespace
}  // namespace metrosync
