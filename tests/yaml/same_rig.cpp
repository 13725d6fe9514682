#include "tests/yaml/same_rig.h"

#include <gtest/gtest.h>

namespace metrosync {

void expectSameRig(const Rig& a, const Rig& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.gravity_m_s2, b.gravity_m_s2);
  EXPECT_EQ(a.platform.mass_kg, b.platform.mass_kg);
  EXPECT_EQ(a.platform.friction, b.platform.friction);
  EXPECT_EQ(a.platform.spring_N_m, b.platform.spring_N_m);
  EXPECT_EQ(a.platform.start_x_m, b.platform.start_x_m);
  EXPECT_EQ(a.platform.start_v_m_s, b.platform.start_v_m_s);
  ASSERT_EQ(a.metronomes.size(), b.metronomes.size());
  for (std::size_t i = 0; i < a.metronomes.size(); ++i) {
    const MetronomeSpec &x = a.metronomes[i], &y = b.metronomes[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.box_mass_kg, y.box_mass_kg);
    EXPECT_EQ(x.pendulum_mass_kg, y.pendulum_mass_kg);
    EXPECT_EQ(x.length_m, y.length_m);
    EXPECT_EQ(x.inertia_kgm2, y.inertia_kgm2);
    EXPECT_EQ(x.damping_kg_s, y.damping_kg_s);
    EXPECT_EQ(x.theta_c_rad, y.theta_c_rad);
    EXPECT_EQ(x.impulse_Nms, y.impulse_Nms);
    EXPECT_EQ(x.locked, y.locked);
    EXPECT_EQ(x.start_angle_rad, y.start_angle_rad);
    EXPECT_EQ(x.start_rate_rad_s, y.start_rate_rad_s);
  }
  EXPECT_EQ(a.sim.t_end_s, b.sim.t_end_s);
  EXPECT_EQ(a.sim.accuracy, b.sim.accuracy);
  EXPECT_EQ(a.sim.integrator, b.sim.integrator);
  EXPECT_EQ(a.sim.sample_s, b.sim.sample_s);
}

}  // namespace metrosync
