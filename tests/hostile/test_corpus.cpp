// The corpus of hostile inputs (tests/hostile/corpus): every file, run with the command line of
// its "# args:" line under 200 MB and 5 s, ends with exit 2, a located message and nothing
// written. Inputs too large to keep in the repository are made here.
#include <sys/stat.h>

#include <fstream>

#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;

std::string argsOf(const fs::path& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  const std::string tag = "# args: ";
  return first.rfind(tag, 0) == 0 ? first.substr(tag.size()) : "run";
}

TEST(HostileCorpus, EveryFileIsRefusedCleanlyAndLocated) {
  const fs::path dir = sourceDir() + "/tests/hostile/corpus";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string rig = entry.path().string();
    const std::string out = testing_support::scratchDir("hostile", "corpus");
    const CommandResult r = runLimited(argsOf(entry.path()) + " " + shellQuote(rig), out);
    expectRefusedCleanly(r, out, rig);
    EXPECT_TRUE(located(r.err.substr(std::string("metrosync: error: ").size()), rig))
        << "not located: " << r.err;
    ++files;
  }
  EXPECT_GE(files, 20);
}

// Paths that are not rig files: read nothing, say what they are.
TEST(HostileCorpus, PathsThatAreNotRigFiles) {
  const std::string scratch = testing_support::scratchDir("hostile", "paths", true);
  const std::string fifo = scratch + "/fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"/dev/zero", "is a device"},
      {"/dev/urandom", "is a device"},
      {scratch, "is a directory"},
      {fifo, "is a FIFO"},
  };
  for (const auto& [path, says] : cases) {
    const std::string out = scratch + "/out";
    const CommandResult r = runLimited("run " + shellQuote(path), out);
    expectRefusedCleanly(r, out, path);
    EXPECT_NE(r.err.find(path + ": " + says), std::string::npos) << r.err;
  }
}

// A file one byte over kMaxRigFileBytes is refused by its size before it is read; one within the
// limit that holds more than the YAML node budget is refused by the budget.
TEST(HostileCorpus, LargeFiles) {
  const std::string scratch = testing_support::scratchDir("hostile", "large", true);
  const std::string big = scratch + "/big.yaml";
  {
    std::ofstream f(big, std::ios::binary);
    const std::string line = "# padding padding padding padding padding padding padding\n";
    for (std::uintmax_t n = 0; n <= kMaxRigFileBytes; n += line.size()) f << line;
  }
  ASSERT_GT(fs::file_size(big), kMaxRigFileBytes);
  CommandResult r = runLimited("run " + shellQuote(big), scratch + "/out");
  expectRefusedCleanly(r, scratch + "/out", big);
  EXPECT_NE(r.err.find("above the 16 MiB limit"), std::string::npos) << r.err;

  // 900000 one-line metronomes (~16 MB): the node budget stops the parse
  const std::string many = scratch + "/many.yaml";
  {
    std::ofstream f(many, std::ios::binary);
    f << "units: physical\nmetronomes:\n";
    for (int i = 0; i < 900000; ++i) f << "  - {box_mass: 1}\n";
  }
  ASSERT_LE(fs::file_size(many), kMaxRigFileBytes);
  r = runLimited("run " + shellQuote(many), scratch + "/out");
  expectRefusedCleanly(r, scratch + "/out", many);
  EXPECT_TRUE(located(r.err.substr(18), many)) << r.err;
  EXPECT_NE(r.err.find("YAML nodes"), std::string::npos) << r.err;
  fs::remove_all(scratch);
}

}  // namespace
}  // namespace metrosync::hostile
