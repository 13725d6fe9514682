// Shared by the hostile-input tests (issue 17): running metrosync under the limits of
// run_limited.sh (200 MB, 5 s), and what a located rig error looks like.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "tests/common/run_metrosync.h"
#include "yaml/rig_loader.h"

namespace metrosync::hostile {

using testing_support::CommandResult;
using testing_support::runMetrosync;
using testing_support::shellQuote;

inline std::string sourceDir() {
  return METROSYNC_SOURCE_DIR;
}

// A shipped rig's path (yaml/rigs/NAME), quoted for the shell.
inline std::string rigPath(const std::string& name) {
  return shellQuote(sourceDir() + "/yaml/rigs/" + name);
}

// `metrosync ARGS --out OUT` under 200 MB of address space and 5 s (killed after: exit 137).
inline CommandResult runLimited(const std::string& args, const std::string& out) {
  testing_support::RunIn in;
  in.env = shellQuote(sourceDir() + "/tests/hostile/run_limited.sh");
  return runMetrosync(args + " --out " + shellQuote(out), in);
}

// Exit 2 (not a kill by the time limit, not bad_alloc under the memory limit), one error line,
// and nothing written: the --out directory absent or empty.
inline void expectRefusedCleanly(const CommandResult& r, const std::string& out,
                                 const std::string& what) {
  EXPECT_EQ(r.code, 2) << what << "\nstderr: " << r.err;
  EXPECT_EQ(r.err.rfind("metrosync: error: ", 0), 0u) << what << "\nstderr: " << r.err;
  namespace fs = std::filesystem;
  EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out)) << what << ": wrote into " << out;
}

// A RigError message is located: "<name>:<line>:<col>: ..." or "<name>: --set ...: ...".
inline bool located(const std::string& msg, const std::string& name) {
  if (msg.rfind(name, 0) != 0) return false;
  static const std::regex where(R"(^:[0-9]+:[0-9]+: |^: --set )");
  return std::regex_search(msg.substr(name.size()), where);
}

// The message of the RigError that loading `text` raises ("" if it loads).
inline std::string loadError(const std::string& text, const std::vector<std::string>& sets = {},
                             const LoadOptions& options = {}) {
  try {
    loadRigText(text, "rig.yaml", sets, options);
  } catch (const RigError& e) {
    return e.what();
  }
  return "";
}

inline std::string shippedRig(const std::string& relative) {
  return testing_support::slurp(sourceDir() + "/yaml/rigs/" + relative);
}

}  // namespace metrosync::hostile
