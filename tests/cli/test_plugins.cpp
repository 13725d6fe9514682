// The plugins (sim/engines/plugin_loader.h, docs/bench/process.md): the direct engine and the
// slow flow run without loading Simbody, LAPACK, Ceres or Cairo; the simbody engine loads its
// plugin; a plugin that is missing or broken is an installation error, exit 2, nothing written.
// What a process loads is read from the dynamic loader's own trace (LD_DEBUG=libs).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/common/run_metrosync.h"

namespace metrosync {
namespace {

using namespace testing_support;
namespace fs = std::filesystem;

const std::string kRig =
    std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/bench/experiment-short.yaml";
const char* kHeavy[] = {"libSimTK",          "liblapack",       "libblas",
                        "libceres",          "libcairo",        "libgfortran",
                        "metrosync-simbody", "metrosync-ceres", "metrosync-animate"};

// The libraries the loader opened ("file=NAME [0];  needed by ..." / "calling init: PATH")
bool loaded(const std::string& trace, const std::string& lib) {
  for (size_t at = trace.find(lib); at != std::string::npos; at = trace.find(lib, at + 1)) {
    const size_t line = trace.rfind('\n', at) + 1;
    const std::string head = trace.substr(line, at - line);
    if (head.find("file=") != std::string::npos || head.find("calling init:") != std::string::npos)
      return true;
  }
  return false;
}

CommandResult tracedRun(const std::string& args, const std::string& out) {
  return runMetrosync(
      "run " + shellQuote(kRig) + " --quiet --no-plot --out " + shellQuote(out) + " " + args,
      {"", "LD_DEBUG=libs"});
}

TEST(Plugins, DirectEngineAndSlowFlowLoadNoHeavyLibrary) {
  for (const std::string args : {"", "--engine direct", "--model slow"}) {
    const std::string out = scratchDir("plugins", "light");
    const CommandResult r = tracedRun(args, out);
    ASSERT_EQ(r.code, 0) << args << "\n" << r.err.substr(0, 2000);
    ASSERT_TRUE(loaded(r.err, "libstdc++")) << "no loader trace: " << r.err.substr(0, 500);
    for (const char* lib : kHeavy) EXPECT_FALSE(loaded(r.err, lib)) << args << " loaded " << lib;
    EXPECT_TRUE(fs::exists(out + "/summary.json"));
  }
}

TEST(Plugins, SimbodyEngineLoadsItsPluginAndSimbody) {
  const std::string out = scratchDir("plugins", "simbody");
  const CommandResult r = tracedRun("--engine simbody", out);
  ASSERT_EQ(r.code, 0) << r.err.substr(0, 2000);
  EXPECT_TRUE(loaded(r.err, "metrosync-simbody.so"));
  EXPECT_TRUE(loaded(r.err, "libSimTKsimbody"));
  EXPECT_FALSE(loaded(r.err, "libceres"));
  EXPECT_FALSE(loaded(r.err, "libcairo"));
  EXPECT_TRUE(fs::exists(out + "/summary.json"));
}

TEST(Plugins, DirectEngineNeedsNoPluginAtAll) {
  const std::string empty = scratchDir("plugins", "nodir", true);
  const std::string out = scratchDir("plugins", "noplugins");
  const CommandResult r =
      runMetrosync("run " + shellQuote(kRig) + " --quiet --no-plot --out " + shellQuote(out),
                   {"", "METROSYNC_PLUGIN_DIR=" + shellQuote(empty)});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out + "/summary.json"));
}

TEST(Plugins, MissingOrBrokenPluginExitsTwoWithNothingWritten) {
  const std::string dir = scratchDir("plugins", "missing", true);
  const std::string out = scratchDir("plugins", "missing_out");
  const std::string env = "METROSYNC_PLUGIN_DIR=" + shellQuote(dir);
  const std::string args =
      "run " + shellQuote(kRig) + " --quiet --engine simbody --out " + shellQuote(out);
  CommandResult r = runMetrosync(args, {"", env});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("metrosync-simbody.so was not found"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(dir), std::string::npos) << r.err;  // where it looked
  EXPECT_FALSE(fs::exists(out));
  // a file of that name that is no shared object
  std::ofstream(dir + "/metrosync-simbody.so") << "not a shared object\n";
  r = runMetrosync(args, {"", env});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("cannot load the plugin " + dir + "/metrosync-simbody.so"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace metrosync
