// RigAtValues (yaml/rig_loader.h): a rig parsed once and built again at other values of some keys
// must be exactly the rig loadRigText builds from the text with those keys' overrides appended,
// and refuse the values it refuses with the same message.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "base/number_text.h"
#include "tests/yaml/same_rig.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

// yaml/rigs/experiment.yaml: two metronomes on a Coulomb platform.
const std::string kPath = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/experiment.yaml";
const std::string kRig = readRigFile(kPath);

// loadRigText with the keys' overrides appended after the rig's own.
Rig loadedAt(const std::vector<std::string>& sets, const std::vector<std::string>& keys,
             const std::vector<double>& values) {
  std::vector<std::string> o = sets;
  for (size_t k = 0; k < keys.size(); ++k) o.push_back(keys[k] + "=" + roundTripText(values[k]));
  return loadRigText(kRig, kPath, o);
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
  const std::vector<std::string> keys = {"platform.friction.mu",
                                         "metronomes.*.pendulum.decay_rate"};
  const RigAtValues rig(kRig, kPath, sets, keys);
  for (const std::vector<double>& v : std::vector<std::vector<double>>{
           {6.5e-4, 0.5}, {1.0 / 3.0, 0.1}, {0.0, 2.0}, {1e-4, 0.5}, {2.5e-3, 1.0 / 7.0}}) {
    const Rig a = rig.at(v), b = loadedAt(sets, keys, v);
    expectSameRig(a, b);
    EXPECT_EQ(a.platform.friction.value("mu"), v[0]);
    EXPECT_EQ(a.platform.mass_kg, 0.2);  // the rig's own overrides stay
  }
}

TEST(RigAtValues, RefusesWhatTheLoaderRefusesWithItsMessage) {
  const std::vector<std::string> keys = {"platform.friction.mu"};
  const RigAtValues rig(kRig, kPath, {}, keys);
  for (double v :
       {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const std::string mine = messageOf([&] { rig.at({v}); });
    EXPECT_EQ(mine, messageOf([&] { loadedAt({}, keys, {v}); })) << v;
    EXPECT_NE(mine, "(no error)") << v;
  }
}

TEST(RigAtValues, AKeyTheRigCannotTakeGivesTheLoadersMessage) {
  for (const std::string key : {"platform.friction.nu", "metronomes.3.pendulum.mass", "units"}) {
    const RigAtValues rig(kRig, kPath, {}, {key});
    const std::string mine = messageOf([&] { rig.at({0.5}); });
    EXPECT_EQ(mine, messageOf([&] { loadedAt({}, {key}, {0.5}); })) << key;
    EXPECT_NE(mine, "(no error)") << key;
  }
}

}  // namespace
}  // namespace metrosync
