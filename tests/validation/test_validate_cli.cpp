// `metrosync validate` from the outside: its options, and that a bad command line writes nothing
// (SPEC 5). The runs themselves are the library's (test_validation_library.cpp runs a tiny plan
// end to end); the full plan is `metrosync validate` itself.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/common/run_metrosync.h"

namespace {

namespace fs = std::filesystem;

using metrosync::testing_support::CommandResult;

// `metrosync ARGS`, stderr folded into out
CommandResult runCli(const std::string& args) {
  CommandResult r = metrosync::testing_support::runMetrosync(args);
  r.out += r.err;
  return r;
}

TEST(ValidateCli, HelpListsTheOptions) {
  const CommandResult r = runCli("validate --help");
  EXPECT_EQ(r.code, 0);
  for (const char* opt : {"--out", "--quick", "--rigs", "--jobs", "report.md"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  EXPECT_NE(runCli("--help").out.find("validate"), std::string::npos);
}

TEST(ValidateCli, MissingRigsIsABadCommandLineAndWritesNothing) {
  const std::string out =
      ::testing::TempDir() + "/metrosync_validate_" + std::to_string(::getpid());
  fs::remove_all(out);
  const CommandResult r = runCli("validate --rigs /nonexistent/rigs --out '" + out + "'");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--rigs"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ValidateCli, BadOptionsAreRejected) {
  EXPECT_EQ(runCli("validate --jobs -3").code, 2);
  EXPECT_EQ(runCli("validate --no-such-option").code, 2);
  EXPECT_EQ(runCli("validate extra-argument").code, 2);
}

}  // namespace
