// Item 8 of issue 17: each message the issue lists now has its location and names the culprit.
// (The corrupted sweep.json and merge wording belong to the sweep code: not here.)
#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

std::string withIntegrators(const std::string& rig, const std::vector<std::string>& sets) {
  LoadOptions o;
  o.integrators = {"verner76", "dopri5"};
  o.integrator_help = "one of: verner76, dopri5";
  return loadError(rig, sets, o);
}

TEST(HostileMessages, UnknownIntegratorIsLocated) {
  std::string rig = shippedRig("experiment.yaml");
  rig += "  integrator: verner77\n";  // the last line of the rig is "  duration: 200 ..."
  const int line = static_cast<int>(std::count(rig.begin(), rig.end(), '\n'));
  const std::string msg = withIntegrators(rig, {});
  EXPECT_EQ(msg.rfind("rig.yaml:" + std::to_string(line) +
                          ":15: simulation.integrator = verner77: unknown integrator (did you "
                          "mean 'verner76'?); one of: verner76, dopri5",
                      0),
            0u)
      << msg;
  const std::string set =
      withIntegrators(shippedRig("experiment.yaml"), {"simulation.integrator=rk45"});
  EXPECT_EQ(set.rfind("rig.yaml: --set simulation.integrator=rk45: ", 0), 0u) << set;
  // a known name loads
  EXPECT_EQ(withIntegrators(shippedRig("experiment.yaml"), {"simulation.integrator=dopri5"}), "");
}

TEST(HostileMessages, EndToEndEachListedMessage) {
  const std::string rigs = sourceDir() + "/yaml/rigs/";
  struct Case {
    std::string args, starts, says;
  };
  const std::string exp = rigs + "experiment.yaml", scaled = rigs + "experiment-scaled.yaml";
  const std::vector<Case> cases = {
      {"run --set simulation.integrator=verner77", "<default rig>: --set simulation.integrator",
       "unknown integrator"},
      {"run " + scaled + " --set units=physical",
       scaled + ": --set units=physical: ", "the rig is written in units: scaled (line 4)"},
      {"run --set \"name=$(printf 'a\\377')\"",
       "<default rig>: --set name=a\\xFF: ", "not UTF-8 text"},
      {"run --set 'name=\"a\\0b\"'",
       "<default rig>: --set name=\"a\\0b\": ", "must not contain control characters"},
      {"run " + exp + " --set 'platform.spring={k: " + std::string(20, '[') + "1" +
           std::string(20, ']') + "}'",
       exp + ": --set platform.spring=", "nested more than"},
  };
  for (const Case& c : cases) {
    const std::string out = testing_support::scratchDir("hostile", "messages");
    const CommandResult r = runLimited(c.args, out);
    expectRefusedCleanly(r, out, c.args);
    EXPECT_EQ(r.err.rfind("metrosync: error: " + c.starts, 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace metrosync::hostile
