// Issue 29: the memory of `basin`, of a sweep's --resume and maps, and of `merge` does not grow
// with the number of points or samples. Each is run for a small and a large count and its peak
// resident memory (wait4's ru_maxrss of the metrosync process itself) compared: the rows stream
// through files (an external sort, tools/report/external_sort.h), only counts and a map slice's
// cells stay in memory. Before, every row was held: ~640 bytes a basin sample, ~1.2 kB a point of
// a resumed sweep or a merge.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "tests/hostile/hostile_support.h"
#include "tools/report/envelope_store.h"
#include "tools/report/sweep_files.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::scratchDir;
using testing_support::slurp;

// What the growth of peak memory between the small and the large run may be. The large runs hold
// 15 000 to 16 000 more rows than the small ones; kept, they cost 10 MB and more (measured on the
// old code: basin +9.9 MB, resume +18 MB, merge +17 MB). A fixed-size process varies by ~1 MB.
constexpr long kMaxGrowthKb = 3000;

struct Peak {
  int code = -1;
  long kb = 0;
};

// Runs `exec env CMD` through /bin/sh (env execs metrosync: the measured process is itself).
Peak peakOf(const std::string& cmd) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string line = "exec env " + cmd + " >/dev/null 2>/dev/null </dev/null";
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  Peak p;
  int status = 0;
  struct rusage ru {};
  if (pid > 0 && ::wait4(pid, &status, 0, &ru) == pid) {
    p.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    p.kb = ru.ru_maxrss;
  }
  return p;
}

std::string binary() {
  return shellQuote(METROSYNC_BINARY);
}

std::string mapRig() {
  return shellQuote(sourceDir() + "/yaml/rigs/experiment-map.yaml");
}

// A PATH without gnuplot: ru_maxrss counts the children metrosync waited for, and gnuplot's own
// ~20 MB would hide the difference.
std::string withoutGnuplot() {
  return "PATH=" + shellQuote(scratchDir("streamed", "path", true));
}

Peak basinPeak(long samples) {
  const std::string out = scratchDir("streamed", "basin" + std::to_string(samples));
  const Peak p = peakOf(withoutGnuplot() + " " + binary() + " basin " + mapRig() +
                        " --random metronomes.0.start.phi=0:2pi --random "
                        "metronomes.1.start.A=1:4 --set simulation.tau=1 --jobs 2 -q --samples " +
                        std::to_string(samples) + " --out " + shellQuote(out));
  // every sample once, in order
  std::ifstream in(out + "/basin.csv");
  std::string line;
  long rows = -1, last = -1;
  while (std::getline(in, line)) {
    if (rows++ < 0) continue;
    const long k = std::stol(line.substr(0, line.find(',')));
    EXPECT_EQ(k, last + 1);
    last = k;
  }
  EXPECT_EQ(rows, samples);
  return p;
}

// Both counts past the external sort's first chunks (kSortChunkBytes of rows: ~16 000 samples
// fill one; its peak is reached by ~24 000, 11-12 MB in all): between 1000 and 16 000 samples the
// chunk's own filling grew the peak by 1.8-2.2 MB, which with the ~1 MB a process varies once
// went past the limit in a loaded `ctest -j2`. 24 000 against 64 000: 0.25-1.3 MB measured (three
// pairs); 40 000 rows kept would cost ~25 MB.
TEST(StreamedMemory, BasinDoesNotGrowWithItsSamples) {
  const Peak small = basinPeak(24000), large = basinPeak(64000);
  ASSERT_EQ(small.code, 0);
  ASSERT_EQ(large.code, 0);
  EXPECT_LT(large.kb - small.kb, kMaxGrowthKb)
      << "peak " << small.kb << " kB at 24000 samples, " << large.kb << " kB at 64000";
}

// A sweep of 40 x 40 x K points whose rows are all in regimes.csv: a first point run (and the run
// stopped as by kill -9, leaving sweep.json), every other row written here.
struct SyntheticSweep {
  std::string dir, args;
  SweepGrid grid;
};

SyntheticSweep syntheticSweep(int k, bool envelopes = false) {
  const std::vector<std::string> vary = {"platform.friction.mu=0.01:0.1:40",
                                         "metronomes.1.alpha=0:0.1:40",
                                         "metronomes.0.start.phi=0:1:" + std::to_string(k)};
  SyntheticSweep s;
  s.dir = scratchDir("streamed", (envelopes ? "kept" : "sweep") + std::to_string(k));
  s.args = "sweep " + mapRig() + " --set simulation.tau=1 --jobs 1 -q";
  if (envelopes) s.args += " --keep envelope";
  std::vector<SweepAxis> axes;
  for (const auto& v : vary) {
    s.args += " --vary " + v;
    axes.push_back(parseVary(v));
  }
  s.grid = SweepGrid(axes);
  testing_support::RunIn killed;
  killed.env = "METROSYNC_SWEEP_STOP_AFTER=1";
  const CommandResult r = runMetrosync(s.args + " --out " + shellQuote(s.dir), killed);
  EXPECT_NE(r.code, 0) << r.err;
  std::optional<EnvelopeStore> store;  // ten rows a point
  if (envelopes) store.emplace(s.dir + "/" + kEnvelopeStoreName, 2, true);
  const std::vector<std::string> rows(10, "1.5,2.25,2.5,3.125,0.75");
  std::ofstream out(s.dir + "/regimes.csv", std::ios::app);
  const char* regimes[] = {"in-phase", "antiphase", "death"};
  for (long g = 0; g < s.grid.size(); ++g) {
    SweepPoint p;
    p.index = g;
    p.regime = regimes[g % 3];
    p.A = {1.0 + 1e-6 * static_cast<double>(g), 2.0};
    p.psi = {0.5};
    p.r = 0.9;
    p.s = 0.1;
    p.tau = 1.0;
    p.complete = true;
    out << formatRegimesRow(s.grid, p) << "\n";
    if (store) store->append(g, rows);
  }
  return s;
}

// Resumed (nothing left to run: the rows sorted, the maps' cells built, gnuplot not on PATH) and
// merged; both hold the same rows, each point once.
struct SweepPeaks {
  Peak resume, merge;
};

SweepPeaks sweepPeaks(int k, bool envelopes = false) {
  const SyntheticSweep s = syntheticSweep(k, envelopes);
  const std::string no_gnuplot = withoutGnuplot();
  SweepPeaks p;
  p.resume =
      peakOf(no_gnuplot + " " + binary() + " " + s.args + " --resume --out " + shellQuote(s.dir));
  const std::string merged = scratchDir("streamed", "merged" + std::to_string(k));
  p.merge = peakOf(no_gnuplot + " " + binary() + " merge -q " + shellQuote(s.dir) + " --out " +
                   shellQuote(merged));
  const std::string rows = slurp(s.dir + "/regimes.csv");
  EXPECT_EQ(std::count(rows.begin(), rows.end(), '\n'), s.grid.size() + 1);
  EXPECT_EQ(slurp(merged + "/regimes.csv"), rows);
  if (envelopes) {  // every point's rows kept once
    long points = 0;
    forEachStoredEnvelope(s.dir + "/" + kEnvelopeStoreName,
                          [&](long, const std::vector<std::string>& r) {
                            ++points;
                            EXPECT_EQ(r.size(), 10u);
                          });
    EXPECT_EQ(points, s.grid.size());
  }
  return p;
}

TEST(StreamedMemory, ResumeMapsAndMergeDoNotGrowWithThePoints) {
  const SweepPeaks small = sweepPeaks(2), large = sweepPeaks(12);  // 3200 and 19200 points
  ASSERT_EQ(small.resume.code, 0);
  ASSERT_EQ(large.resume.code, 0);
  ASSERT_EQ(small.merge.code, 0);
  ASSERT_EQ(large.merge.code, 0);
  EXPECT_LT(large.resume.kb - small.resume.kb, kMaxGrowthKb)
      << "--resume: peak " << small.resume.kb << " kB at 3200 points, " << large.resume.kb
      << " kB at 19200";
  EXPECT_LT(large.merge.kb - small.merge.kb, kMaxGrowthKb)
      << "merge: peak " << small.merge.kb << " kB at 3200 points, " << large.merge.kb
      << " kB at 19200";
}

// --keep envelope: the resume reads the store's points and rewrites it one point at a time (before:
// the whole decompressed store in memory, twice).
TEST(StreamedMemory, ResumeWithEnvelopesDoesNotGrowWithThePoints) {
  const SweepPeaks small = sweepPeaks(2, true), large = sweepPeaks(12, true);
  ASSERT_EQ(small.resume.code, 0);
  ASSERT_EQ(large.resume.code, 0);
  EXPECT_LT(large.resume.kb - small.resume.kb, kMaxGrowthKb)
      << "--resume --keep envelope: peak " << small.resume.kb << " kB at 3200 points, "
      << large.resume.kb << " kB at 19200";
}

}  // namespace
}  // namespace metrosync::hostile
