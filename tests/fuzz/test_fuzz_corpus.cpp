// Every input of tools/fuzz/corpus/<target>/ (the findings of libFuzzer's runs, each a regression
// case, and the seeds written for the targets the shipped rigs do not cover) through the fuzz
// targets' bodies (tools/fuzz/fuzz_entries.h) in the ordinary build: none may be a finding or end
// in an exception the body does not expect. The sanitizer stage runs this folder too.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tools/fuzz/fuzz_entries.h"

namespace metrosync::fuzz {
namespace {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FuzzCorpus, EveryInputPassesItsTarget) {
  const fs::path corpus = fs::path(METROSYNC_SOURCE_DIR) / "tools/fuzz/corpus";
  for (const Target& t : targets()) {
    const fs::path dir = corpus / t.name;
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    int inputs = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
      if (!e.is_regular_file()) continue;
      ++inputs;
      try {
        t.run(bytesOf(e.path()));
      } catch (const std::exception& x) {
        ADD_FAILURE() << t.name << " " << e.path().filename() << ": " << x.what();
      }
    }
    EXPECT_GT(inputs, 0) << dir;
  }
}

// The split of an input into a text and its --set parts, and a finding as a finding.
TEST(FuzzCorpus, TheBodiesSeeWhatTheyMust) {
  using namespace std::string_literals;
  EXPECT_EQ(nulSeparated("a\0b\0\0c"s), (std::vector<std::string>{"a", "b", "", "c"}));
  EXPECT_EQ(nulSeparated(""), std::vector<std::string>{""});
  EXPECT_NO_THROW(rigLoader("units: physical\nname: [\n"));  // refused, located
  EXPECT_NO_THROW(keyPath("metronomes.*.nu=0.5"));
  EXPECT_NO_THROW(options("sweep\0--vary\0platform.friction.mu=0:1:3"s));  // its length, no count
  EXPECT_NO_THROW(dataFile("t,theta_1\n0,0.1\n0.5,\n1,0.2\n"));
}

}  // namespace
}  // namespace metrosync::fuzz
