// `metrosync validate` from the outside: its options, and that a bad command line writes nothing
// (SPEC 5). The runs themselves are the library's (test_validation_library.cpp runs a tiny plan
// end to end); the full plan is `metrosync validate` itself.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out;
};

// `metrosync ARGS` with stderr folded into stdout
Result metrosync(const std::string& args) {
  const std::string cmd = std::string("'") + METROSYNC_BINARY + "' " + args + " 2>&1";
  Result r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

TEST(ValidateCli, HelpListsTheOptions) {
  const Result r = metrosync("validate --help");
  EXPECT_EQ(r.code, 0);
  for (const char* opt : {"--out", "--quick", "--rigs", "--jobs", "report.md"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  EXPECT_NE(metrosync("--help").out.find("validate"), std::string::npos);
}

TEST(ValidateCli, MissingRigsIsABadCommandLineAndWritesNothing) {
  const std::string out =
      ::testing::TempDir() + "/metrosync_validate_" + std::to_string(::getpid());
  fs::remove_all(out);
  const Result r = metrosync("validate --rigs /nonexistent/rigs --out '" + out + "'");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--rigs"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ValidateCli, BadOptionsAreRejected) {
  EXPECT_EQ(metrosync("validate --jobs -3").code, 2);
  EXPECT_EQ(metrosync("validate --no-such-option").code, 2);
  EXPECT_EQ(metrosync("validate extra-argument").code, 2);
}

}  // namespace
