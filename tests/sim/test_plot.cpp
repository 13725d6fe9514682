// Plots: written atomically when gnuplot is there, skipped with a warning when it is not.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "base/constants.h"
#include "tools/report/plot.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;

std::string freshDir(const std::string& name) {
  const std::string d =
      ::testing::TempDir() + "/metrosync_plot_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(d);
  return d;
}

std::vector<std::string> listDir(const std::string& d) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(d)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<EnvelopeRow> demo(int n, double psi_rate) {
  std::vector<EnvelopeRow> rows;
  for (long k = 0; k < 600; ++k) {
    EnvelopeRow r;
    r.tau = envelopeTau(0.073, k);
    for (int i = 0; i < n; ++i) r.A.push_back(1.9 - 0.3 * i * (1 - std::exp(-r.tau / 40)));
    for (int j = 1; j < n; ++j) r.psi.push_back(0.03 + j * psi_rate * r.tau);
    rows.push_back(r);
  }
  return rows;
}

bool isPng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in && std::string(magic + 1, 3) == "PNG";
}

// Sets PATH for the life of the object.
struct ScopedPath {
  explicit ScopedPath(const char* value) {
    const char* old = std::getenv("PATH");
    had_ = old != nullptr;
    if (had_) old_ = old;
    ::setenv("PATH", value, 1);
  }
  ~ScopedPath() {
    if (had_)
      ::setenv("PATH", old_.c_str(), 1);
    else
      ::unsetenv("PATH");
  }
  bool had_ = false;
  std::string old_;
};

TEST(Plot, ScriptDrawsThresholdAndPhaseGuides) {
  const std::string s =
      gnuplotScript("/d/it's.dat", "/d/out.png", 2, 1, {0.9, 0.9}, 300, 0.0, 2 * kPi, "rig");
  EXPECT_NE(s.find("set terminal pngcairo"), std::string::npos);
  EXPECT_NE(s.find("'/d/it''s.dat'"), std::string::npos);  // quote doubled for gnuplot
  EXPECT_NE(s.find("0.9 with lines"), std::string::npos);  // theta_c, once for equal values
  EXPECT_EQ(s.find("0.9 with lines"), s.rfind("0.9 with lines"));
  EXPECT_NE(s.find("pi with lines"), std::string::npos);
  EXPECT_NE(s.find("2*pi with lines"), std::string::npos);
  EXPECT_NE(s.find("\"π\""), std::string::npos);  // tics in units of pi
  EXPECT_NE(s.find("layout 2,1"), std::string::npos);
  // one metronome: amplitudes only
  const std::string one = gnuplotScript("d", "p", 1, 1, {0.9}, 300, 0, 2 * kPi, "rig");
  EXPECT_NE(one.find("layout 1,1"), std::string::npos);
  EXPECT_EQ(one.find("ψ"), std::string::npos);
  // comparison: both models, slow dashed
  const std::string cmp = gnuplotScript("d", "p", 2, 2, {0.9, 1.1}, 300, 0, 2 * kPi, "rig");
  EXPECT_NE(cmp.find("A_1 slow"), std::string::npos);
  EXPECT_NE(cmp.find("index 1"), std::string::npos);
  EXPECT_NE(cmp.find("1.1 with lines"), std::string::npos);
}

TEST(Plot, MissingGnuplotIsSkippedQuietlyForTheRun) {
  OutputDir dir(freshDir("missing"));
  bool written = true;
  {
    ScopedPath p("/nonexistent-metrosync-dir");
    written = plotEnvelope(dir, "envelope.png", demo(2, 0.0), {0.9, 0.9}, "rig");
  }
  EXPECT_FALSE(written);
  EXPECT_TRUE(listDir(dir.path()).empty());
}

TEST(Plot, WritesAPngAndNoTemporaryFile) {
  if (findExecutable("gnuplot").empty()) GTEST_SKIP() << "gnuplot not installed";
  OutputDir dir(freshDir("png"));
  ASSERT_TRUE(plotEnvelope(dir, "envelope.png", demo(2, 0.2), {0.9, 0.9}, "test rig: drift"));
  ASSERT_TRUE(plotComparison(dir, "comparison.png", demo(3, 0.001), demo(3, 0.0012),
                             {0.9, 0.9, 0.9}, "test rig: compare"));
  ASSERT_TRUE(plotEnvelope(dir, "one.png", demo(1, 0), {0.9}, "single"));
  EXPECT_EQ(listDir(dir.path()),
            (std::vector<std::string>{"comparison.png", "envelope.png", "one.png"}));
  for (const auto& f : listDir(dir.path())) EXPECT_TRUE(isPng(dir.file(f))) << f;
}

TEST(Plot, NoRowsNoPlot) {
  if (findExecutable("gnuplot").empty()) GTEST_SKIP() << "gnuplot not installed";
  OutputDir dir(freshDir("empty"));
  EXPECT_FALSE(plotEnvelope(dir, "envelope.png", {}, {0.9, 0.9}, "rig"));
  EXPECT_TRUE(listDir(dir.path()).empty());
}

TEST(Plot, FindExecutableLooksOnPath) {
  EXPECT_FALSE(findExecutable("sh").empty());
  EXPECT_TRUE(findExecutable("metrosync-no-such-program").empty());
}

}  // namespace
}  // namespace metrosync
