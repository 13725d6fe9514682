// The one trajectory row maker of both engines (sim/record/trajectory_row.h): a row's numbers in
// the rig's units, held against the scales written out by hand, a locked metronome's columns 0,
// the platform column by the law's kind of contact.
#include <gtest/gtest.h>

#include <vector>

#include "models/rig.h"
#include "models/scaling.h"
#include "sim/record/trajectory_row.h"

namespace metrosync {
namespace {

Rig threeMetronomes(Units units, bool middle_locked) {
  Rig rig;
  rig.units = units;
  rig.metronomes.resize(3);
  rig.metronomes[1].locked = middle_locked;
  return rig;
}

ScaledParams scales() {
  ScaledParams sp;
  sp.time_scale_s = 0.25;  // omega0 = 4 / s
  sp.angle_scale = 0.5;
  sp.x_scale_m = 0.125;
  return sp;
}

// the state's pendulum j: angle 0.1 (j + 1), rate -0.2 (j + 1)
double theta(int j) {
  return 0.1 * (j + 1);
}
double omega(int j) {
  return -0.2 * (j + 1);
}

TEST(TrajectoryRow, APhysicalRigsRowIsTheStateInSIUnits) {
  const Rig rig = threeMetronomes(Units::Physical, true);
  const TrajectoryRow maker(rig, scales(), swingingPendulums(rig));
  std::vector<double> row;
  maker.fill(row, 1.5, 0.01, -0.02, theta, omega, -1);
  const std::vector<double> want = {1.5, 0.01, -0.02, 0.1, -0.2, 0.0, 0.0, 0.2, -0.4, -1};
  EXPECT_EQ(row, want);
  EXPECT_EQ(maker.size(), want.size());
}

TEST(TrajectoryRow, AScaledRigsRowIsInItsScaledVariables) {
  const Rig rig = threeMetronomes(Units::Scaled, false);
  const TrajectoryRow maker(rig, scales(), swingingPendulums(rig));
  std::vector<double> row(3, 7.0);  // resized, every number written
  maker.fill(row, 1.5, 0.01, -0.02, theta, omega, 0);
  // t omega0, x / x_scale, xdot / (x_scale omega0), theta / angle_scale, thetadot / (angle_scale
  // omega0)
  const std::vector<double> want = {6.0, 0.08, -0.04, 0.2, -0.1, 0.4, -0.2, 0.6, -0.3, 0};
  ASSERT_EQ(row.size(), want.size());
  for (std::size_t k = 0; k < want.size(); ++k) EXPECT_NEAR(row[k], want[k], 1e-15) << k;
}

TEST(TrajectoryRow, EachMetronomeReadsItsOwnPendulum) {
  Rig rig = threeMetronomes(Units::Physical, false);
  rig.metronomes[0].locked = true;
  EXPECT_EQ(swingingPendulums(rig), (std::vector<int>{-1, 0, 1}));
  // an engine whose pendulums are in another order (Simbody's system): metronome 2 is pendulum 0
  const TrajectoryRow maker(rig, scales(), {-1, 1, 0});
  std::vector<double> row;
  maker.fill(row, 0.0, 0.0, 0.0, theta, omega, 1);
  EXPECT_EQ(row, (std::vector<double>{0, 0, 0, 0, 0, 0.2, -0.4, 0.1, -0.2, 1}));
}

TEST(TrajectoryRow, ThePlatformColumnIsTheModeOrTheSlipDirection) {
  EXPECT_EQ(TrajectoryRow::column(true, 0, 0.3), 0);  // set-valued: stuck whatever v says
  EXPECT_EQ(TrajectoryRow::column(true, -1, 0.0), -1);
  EXPECT_EQ(TrajectoryRow::column(false, 0, 0.3), 1);  // otherwise the sign of v
  EXPECT_EQ(TrajectoryRow::column(false, 0, -1e-300), -1);
  EXPECT_EQ(TrajectoryRow::column(false, 1, 0.0), 0);
}

}  // namespace
}  // namespace metrosync
