// RigAtValues (yaml/rig_loader.h): a rig parsed once and built again at other values of some keys
// must be exactly the rig loadRigText builds from the text with those keys' overrides appended,
// and refuse the values it refuses with the same message.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "base/number_text.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

const char* const kRig = R"(units: physical
platform:
  mass: 0.15
  friction: {law: coulomb, mu: 6.5e-4}
metronomes:
  - box_mass: 0.06
    pendulum: {mass: 0.0226, length: 0.0225, damping: 0.0226}
    escapement: {angle: 0.244, impulse: 1.5e-5}
    start: {angle: 0.5, rate: 0.0}
  - box_mass: 0.06
    pendulum: {mass: 0.0226, length: 0.0225, damping: 0.0226}
    escapement: {angle: 0.244, impulse: 1.5e-5}
simulation:
  duration: 100
)";

void expectSameRig(const Rig& a, const Rig& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.gravity_m_s2, b.gravity_m_s2);
  EXPECT_EQ(a.platform.mass_kg, b.platform.mass_kg);
  EXPECT_EQ(a.platform.friction.values(), b.platform.friction.values());
  EXPECT_EQ(a.platform.spring_N_m, b.platform.spring_N_m);
  EXPECT_EQ(a.platform.start_x_m, b.platform.start_x_m);
  EXPECT_EQ(a.platform.start_v_m_s, b.platform.start_v_m_s);
  ASSERT_EQ(a.metronomes.size(), b.metronomes.size());
  for (size_t i = 0; i < a.metronomes.size(); ++i) {
    const MetronomeSpec &m = a.metronomes[i], &n = b.metronomes[i];
    EXPECT_EQ(m.name, n.name);
    EXPECT_EQ(m.box_mass_kg, n.box_mass_kg);
    EXPECT_EQ(m.pendulum_mass_kg, n.pendulum_mass_kg);
    EXPECT_EQ(m.length_m, n.length_m);
    EXPECT_EQ(m.inertia_kgm2, n.inertia_kgm2);
    EXPECT_EQ(m.damping_kg_s, n.damping_kg_s);
    EXPECT_EQ(m.theta_c_rad, n.theta_c_rad);
    EXPECT_EQ(m.impulse_Nms, n.impulse_Nms);
    EXPECT_EQ(m.locked, n.locked);
    EXPECT_EQ(m.start_angle_rad, n.start_angle_rad);
    EXPECT_EQ(m.start_rate_rad_s, n.start_rate_rad_s);
  }
  EXPECT_EQ(a.sim.t_end_s, b.sim.t_end_s);
  EXPECT_EQ(a.sim.accuracy, b.sim.accuracy);
}

// loadRigText with the keys' overrides appended after the rig's own.
Rig loadedAt(const std::vector<std::string>& sets, const std::vector<std::string>& keys,
             const std::vector<double>& values) {
  std::vector<std::string> o = sets;
  for (size_t k = 0; k < keys.size(); ++k) o.push_back(keys[k] + "=" + roundTripText(values[k]));
  return loadRigText(kRig, "rig.yaml", o);
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const RigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RigAtValues, EqualsLoadingTheTextWithTheKeysSet) {
  const std::vector<std::string> sets = {"platform.mass=0.2", "metronomes.1.start.angle=-0.3"};
  const std::vector<std::string> keys = {"platform.friction.mu", "metronomes.*.pendulum.damping"};
  const RigAtValues rig(kRig, "rig.yaml", sets, keys);
  for (const std::vector<double>& v : std::vector<std::vector<double>>{
           {6.5e-4, 0.0226}, {1.0 / 3.0, 0.01}, {0.0, 0.1}, {1e-4, 0.0226}, {2.5e-3, 3e-2}}) {
    const Rig a = rig.at(v), b = loadedAt(sets, keys, v);
    expectSameRig(a, b);
    EXPECT_EQ(a.platform.friction.value("mu"), v[0]);
    EXPECT_EQ(a.metronomes[1].damping_kg_s, v[1]);
    EXPECT_EQ(a.platform.mass_kg, 0.2);  // the rig's own overrides stay
  }
}

TEST(RigAtValues, RefusesWhatTheLoaderRefusesWithItsMessage) {
  const std::vector<std::string> keys = {"platform.friction.mu"};
  const RigAtValues rig(kRig, "rig.yaml", {}, keys);
  for (double v :
       {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const std::string mine = messageOf([&] { rig.at({v}); });
    EXPECT_EQ(mine, messageOf([&] { loadedAt({}, keys, {v}); })) << v;
    EXPECT_NE(mine, "(no error)") << v;
  }
}

TEST(RigAtValues, AKeyTheRigCannotTakeGivesTheLoadersMessage) {
  for (const std::string key : {"platform.friction.nu", "metronomes.3.pendulum.mass", "units"}) {
    const RigAtValues rig(kRig, "rig.yaml", {}, {key});
    const std::string mine = messageOf([&] { rig.at({0.5}); });
    EXPECT_EQ(mine, messageOf([&] { loadedAt({}, {key}, {0.5}); })) << key;
    EXPECT_NE(mine, "(no error)") << key;
  }
}

}  // namespace
}  // namespace metrosync
