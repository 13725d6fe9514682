// A seeded mutation fuzz loop over the shipped rigs (issue 17): the loader never crashes and
// either loads or throws RigError with a location. A fixed number of mutants (seconds in CI).
#include <cstdlib>
#include <random>

#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;

// Tokens that break YAML and the loader in interesting ways.
const std::vector<std::string> kTokens = {"&a ",
                                          "*a",
                                          "[",
                                          "]",
                                          "{",
                                          "}",
                                          ": ",
                                          "- ",
                                          "\n",
                                          "  ",
                                          "---\n",
                                          "...\n",
                                          "\"",
                                          "'",
                                          "\\u0000",
                                          "\\ud800",
                                          "\xFF",
                                          "\xC3",
                                          std::string("\0", 1),
                                          "\t",
                                          "1e308",
                                          "-1",
                                          ".nan",
                                          ".inf",
                                          "0",
                                          "1e-300",
                                          "!!binary ",
                                          "? ",
                                          "|",
                                          ">",
                                          "#",
                                          "%YAML 1.2\n",
                                          "<<: *a\n"};

std::string mutate(std::string s, std::mt19937& rng) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int k = 0; k < edits && !s.empty(); ++k) {
    const std::size_t at = rng() % s.size();
    switch (rng() % 5) {
      case 0:  // flip a byte
        s[at] = static_cast<char>(rng() & 0xFF);
        break;
      case 1:  // delete a run
        s.erase(at, 1 + rng() % 8);
        break;
      case 2:  // insert a token
        s.insert(at, kTokens[rng() % kTokens.size()]);
        break;
      case 3: {  // duplicate a run (repetition, deeper structure)
        const std::string run = s.substr(at, 1 + rng() % 64);
        s.insert(at, run);
        break;
      }
      default:  // swap two lines' worth of text
        std::swap(s[at], s[rng() % s.size()]);
    }
  }
  return s;
}

TEST(HostileFuzz, LoaderLoadsOrThrowsALocatedRigError) {
  std::vector<std::string> seeds;
  for (const auto& e : fs::recursive_directory_iterator(sourceDir() + "/yaml/rigs"))
    if (e.path().extension() == ".yaml") seeds.push_back(testing_support::slurp(e.path()));
  ASSERT_GE(seeds.size(), 10u);
  // METROSYNC_FUZZ_MUTANTS / METROSYNC_FUZZ_SEED: a longer or different run by hand
  const char* n_env = std::getenv("METROSYNC_FUZZ_MUTANTS");
  const char* seed_env = std::getenv("METROSYNC_FUZZ_SEED");
  std::mt19937 rng(seed_env ? std::stoul(seed_env) : 17u);  // issue 17
  const int kMutants = n_env ? std::stoi(n_env) : 3000;
  int loaded = 0, refused = 0;
  for (int i = 0; i < kMutants; ++i) {
    const std::string text = mutate(seeds[rng() % seeds.size()], rng);
    try {
      loadRigText(text, "fuzz.yaml");
      ++loaded;
    } catch (const RigError& e) {
      ++refused;
      const std::string msg = e.what();
      ASSERT_TRUE(located(msg, "fuzz.yaml")) << "mutant " << i << ": " << msg.substr(0, 300);
    } catch (const std::exception& e) {
      FAIL() << "mutant " << i << ": not a RigError: " << e.what();
    }
  }
  // both outcomes occur, or the mutations test nothing
  EXPECT_GT(loaded, 0);
  EXPECT_GT(refused, kMutants / 2);
}

}  // namespace
}  // namespace metrosync::hostile
