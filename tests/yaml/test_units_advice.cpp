// A key of the other units (issue 37, yaml/units_advice.h): refused as before ("only with units:
// scaled"), and now naming the key of the rig's own units that sets the same thing, in a file,
// a --set and an option's key alike.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

const std::string kSource = METROSYNC_SOURCE_DIR;

std::string loadError(const std::string& text, const std::vector<std::string>& sets) {
  try {
    loadRigText(text, "rig.yaml", sets);
  } catch (const RigError& e) {
    return e.what();
  }
  return "(loaded)";
}

std::string scaledRig() {
  return "units: scaled\nepsilon: 0.073\nplatform:\n  friction: {law: coulomb, mu: 0.4}\n"
         "metronomes:\n  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.03}}\n"
         "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.0}}\n"
         "simulation:\n  tau: 10\n";
}

TEST(UnitsAdvice, AScaledKeyOnAPhysicalRigNamesThePhysicalKeys) {
  const std::string phys = defaultRigYaml();
  const struct {
    std::string set, says;
  } cases[] = {
      {"metronomes.1.start.phi=3.54",
       "metronomes.1.start.phi: only with units: scaled (this rig is physical: set "
       "metronomes.1.start.angle (rad) and metronomes.1.start.rate (rad/s))"},
      {"metronomes.*.nu=0.6",
       "metronomes.*.nu: only with units: scaled (this rig is physical: set "
       "metronomes.*.pendulum.damping (kg/s) or metronomes.*.pendulum.decay_rate (1/s))"},
      {"metronomes.0.J=3",
       "set metronomes.0.escapement.impulse (N m s) or "
       "metronomes.0.escapement.steady_amplitude (rad)"},
      {"metronomes.1.alpha=1",
       "set metronomes.1.pendulum.length (m) or "
       "metronomes.1.pendulum.inertia (kg m^2)"},
      {"epsilon=0.1", "epsilon follows from the masses: set platform.mass (kg)"},
      {"simulation.tau=100", "set simulation.duration (s)"},
  };
  for (const auto& c : cases) {
    const std::string e = loadError(phys, {c.set});
    EXPECT_NE(e.find(c.says), std::string::npos) << c.set << "\n" << e;
    EXPECT_EQ(e.rfind("rig.yaml: --set " + c.set + ": ", 0), 0u) << e;
  }
}

TEST(UnitsAdvice, APhysicalKeyOnAScaledRigNamesTheScaledKeys) {
  const std::string e = loadError(scaledRig(), {"metronomes.0.pendulum.length=0.02"});
  EXPECT_NE(e.find("metronomes.0.pendulum: only with units: physical (this rig is scaled: set "
                   "metronomes.0.nu, metronomes.0.alpha and metronomes.0.zeta)"),
            std::string::npos)
      << e;
  const std::string start = loadError(scaledRig(), {"metronomes.1.start.angle=0.1"});
  EXPECT_NE(start.find("set metronomes.1.start.theta (or metronomes.1.start.A and "
                       "metronomes.1.start.phi), in scaled units"),
            std::string::npos)
      << start;
  // written in the file, located there
  const std::string in_file = loadError(scaledRig() + "gravity: 9.81\n", {});
  EXPECT_NE(in_file.find("rig.yaml:10:1: gravity = 9.81: only with units: physical (this rig is "
                         "scaled: a scaled rig has g = 1: leave gravity out)"),
            std::string::npos)
      << in_file;
}

// The option keys (--param, --vary, ...) go through the same resolver: the same advice.
TEST(UnitsAdvice, AnOptionsKeyGetsTheSameAdvice) {
  const std::string path = kSource + "/yaml/rigs/experiment.yaml";
  try {
    resolveRigKey(readRigFile(path), path, {}, "metronomes.1.alpha", "--param metronomes.1.alpha");
    ADD_FAILURE() << "resolved";
  } catch (const RigError& e) {
    EXPECT_NE(std::string(e.what()).find("set metronomes.1.pendulum.length (m)"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace metrosync
