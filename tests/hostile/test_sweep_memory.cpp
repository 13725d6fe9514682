// Issue 29: a sweep's memory does not grow with its points. Its rows stay in regimes.csv as they
// finish; the end sorts the file through an external sort of bounded memory (sortRegimesCsv,
// tools/report/external_sort.h). Checked here with runs of a few rows and of one row (more runs
// than are merged at once: two levels), against the in-memory sort of the same rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "tests/common/run_metrosync.h"
#include "tools/report/external_sort.h"
#include "tools/report/sweep_files.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;
using testing_support::scratchDir;
using testing_support::slurp;

SweepPoint pointAt(long g, const std::string& message) {
  SweepPoint p;
  p.index = g;
  p.regime = g % 3 == 0 ? "in-phase" : "antiphase";
  p.A = {1.0 + 0.01 * static_cast<double>(g), 2.0};
  p.psi = {0.5};
  p.r = 0.9;
  p.s = 0.1;
  p.tau = 10.0;
  p.complete = true;
  p.message = message;
  return p;
}

TEST(SweepMemory, SortingInBoundedPassesEqualsOneSort) {
  const SweepGrid grid({parseVary("platform.friction.mu=0:1:200")});
  const std::string d = scratchDir("memory", "sort", true);
  std::vector<long> order(200);
  for (long g = 0; g < 200; ++g) order[g] = g;
  std::shuffle(order.begin(), order.end(), std::mt19937(29));
  std::map<long, std::string> expected;  // the last row of each index kept, odd shard only
  std::string text = regimesHeader(grid, 2) + "\n";
  for (long g : order) {
    const std::string row = formatRegimesRow(grid, pointAt(g, "first"));
    text += row + "\n";
    if (g % 2 == 1) expected[g] = row;
  }
  for (long g : {7L, 31L, 8L}) {  // points run again: their later rows win
    const std::string row = formatRegimesRow(grid, pointAt(g, "again"));
    text += row + "\n";
    if (g % 2 == 1) expected[g] = row;
  }
  text += "not,a,row\n";  // malformed: dropped
  text += "0.5,in-ph";    // a last line cut short: dropped
  const auto keep = [](long g) { return g % 2 == 1; };
  std::string sorted_once;
  for (std::size_t pass : {std::size_t(1) << 30, std::size_t(400), std::size_t(1)}) {
    const std::string path = d + "/regimes-" + std::to_string(pass) + ".csv";
    std::ofstream(path) << text;
    sortRegimesCsv(path, grid, 2, keep, pass);  // 400 bytes: a few rows a run; 1: one row
    const std::string sorted = slurp(path);
    if (sorted_once.empty()) {
      sorted_once = sorted;
      std::string want = regimesHeader(grid, 2) + "\n";
      for (const auto& [g, row] : expected) want += row + "\n";
      EXPECT_EQ(sorted, want);
    }
    EXPECT_EQ(sorted, sorted_once) << "pass of " << pass << " bytes";
  }
  EXPECT_NE(sorted_once.find("again"), std::string::npos);
}

// The sort itself: every line once, ascending, lines of one index in the order added, whatever the
// size of a run; read twice alike; never more lines held than fit in a run.
TEST(SweepMemory, ExternalSortIsStableAndBounded) {
  const std::string d = scratchDir("memory", "external", true);
  std::vector<std::pair<long, std::string>> lines;
  std::mt19937 draw(29);
  for (int k = 0; k < 500; ++k) {
    const long g = static_cast<long>(draw() % 97);
    lines.emplace_back(g, "line " + std::to_string(k) + " of " + std::to_string(g));
  }
  std::vector<std::pair<long, std::string>> want = lines;
  std::stable_sort(want.begin(), want.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t chunk : {std::size_t(1) << 30, std::size_t(300), std::size_t(1)}) {
    ExternalSort sort(d, chunk);
    for (const auto& [g, text] : lines) sort.add(g, text);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::pair<long, std::string>> got;
      sort.forEach([&](long g, const std::string& text) { got.emplace_back(g, text); });
      EXPECT_EQ(got, want) << "runs of " << chunk << " bytes, reading " << pass;
    }
    if (chunk < 1000) {
      EXPECT_LE(sort.maxLinesHeld(), chunk / 20 + 1) << chunk;
    }
  }
  EXPECT_TRUE(fs::is_empty(d)) << "the runs' private folders are removed";
}

}  // namespace
}  // namespace metrosync
