// comparison.csv and the full-vs-slow differences on synthetic envelopes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "base/constants.h"
#include "sim/analysis/compare.h"
#include "tools/report/comparison_csv.h"
#include "tools/report/outputs.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;
constexpr double kEps = 0.05;

std::string freshDir(const std::string& name) {
  const std::string d =
      ::testing::TempDir() + "/metrosync_compare_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string l;
  while (std::getline(in, l)) lines.push_back(l);
  return lines;
}

// rows k = k0 .. k1-1 of a two-metronome envelope
std::vector<EnvelopeRow> rows(long k0, long k1, double dA1, double dA2, double psi_shift) {
  std::vector<EnvelopeRow> out;
  for (long k = k0; k < k1; ++k) {
    const double tau = envelopeTau(kEps, k);
    out.push_back({tau, {1.5 + dA1 * std::sin(tau), 1.2 + dA2}, {0.3 * tau + psi_shift}});
  }
  return out;
}

TEST(Compare, MaxDifferencesAndWhereTheyOccur) {
  const auto slow = rows(0, 400, 0.0, 0.0, 0.0);
  const auto full = rows(0, 400, 0.02, -0.01, 0.04);
  const std::string dir = freshDir("max");
  const ComparisonResult r = writeComparisonCsv(full, slow, kEps, dir + "/comparison.csv");
  ASSERT_EQ(r.max_abs_dA.size(), 2u);
  ASSERT_EQ(r.max_abs_dpsi.size(), 1u);
  // |0.02 sin(tau)| at its largest on the grid
  double expected = 0.0;
  for (const auto& row : slow) expected = std::max(expected, 0.02 * std::fabs(std::sin(row.tau)));
  EXPECT_GT(expected, 0.019);
  EXPECT_NEAR(r.max_abs_dA[0], expected, 1e-12);
  EXPECT_NEAR(0.02 * std::fabs(std::sin(r.tau_max_dA[0])), expected, 1e-12);
  EXPECT_NEAR(r.max_abs_dA[1], 0.01, 1e-12);
  EXPECT_NEAR(r.max_abs_dpsi[0], 0.04, 1e-9);
  EXPECT_EQ(r.rows, 400);
  EXPECT_EQ(r.unmatched_full + r.unmatched_slow, 0);
  // the analysis without the file (sim/analysis) gives the writer's numbers (tools/report)
  const ComparisonResult values = compareEnvelopes(full, slow, kEps);
  EXPECT_EQ(values.max_abs_dA, r.max_abs_dA);
  EXPECT_EQ(values.tau_max_dpsi, r.tau_max_dpsi);
  EXPECT_EQ(values.rows, r.rows);
}

TEST(Compare, PhasesAreComparedModuloTwoPi) {
  // the full model's psi sits three turns away (a long drift) and 0.05 rad ahead
  const auto slow = rows(0, 100, 0, 0, 0.0);
  const auto full = rows(0, 100, 0, 0, 6 * kPi + 0.05);
  ComparisonResult r = compareEnvelopes(full, slow, kEps);
  EXPECT_NEAR(r.max_abs_dpsi[0], 0.05, 1e-9);
  // differences just short of +-pi on either side of the branch cut are near pi, not 2 pi
  const auto across = rows(0, 100, 0, 0, -(2 * kPi - 0.1));
  r = compareEnvelopes(across, slow, kEps);
  EXPECT_NEAR(r.max_abs_dpsi[0], 0.1, 1e-9);
  const auto half = rows(0, 100, 0, 0, kPi - 0.01);
  r = compareEnvelopes(half, slow, kEps);
  EXPECT_NEAR(r.max_abs_dpsi[0], kPi - 0.01, 1e-9);
}

TEST(Compare, CsvHasTheSpecColumnsAndOneLinePerMatchedRow) {
  const auto slow = rows(0, 50, 0, 0, 0);
  const auto full = rows(0, 50, 0.1, 0.2, 0.3);
  const std::string path = freshDir("csv") + "/comparison.csv";
  writeComparisonCsv(full, slow, kEps, path);
  const auto lines = readLines(path);
  ASSERT_EQ(lines.size(), 51u);
  EXPECT_EQ(lines[0], "tau,A_1_full,A_1_slow,A_2_full,A_2_slow,psi_2_full,psi_2_slow");
  // each model's values as they are (psi not moved between branches)
  std::stringstream ss(lines[10]);
  std::vector<double> v;
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
  ASSERT_EQ(v.size(), 7u);
  EXPECT_NEAR(v[0], full[9].tau, 1e-9);
  EXPECT_NEAR(v[1], full[9].A[0], 1e-11);
  EXPECT_NEAR(v[2], slow[9].A[0], 1e-11);
  EXPECT_NEAR(v[3], full[9].A[1], 1e-11);
  EXPECT_NEAR(v[4], slow[9].A[1], 1e-11);
  EXPECT_NEAR(v[5], full[9].psi[0], 1e-11);
  EXPECT_NEAR(v[6], slow[9].psi[0], 1e-11);
}

TEST(Compare, RowsAreMatchedOnTheGridIndex) {
  // the full run stopped at row 60 and missed rows 10..14; the slow flow has rows 0..99
  auto full = rows(0, 10, 0.0, 0.5, 0);
  const auto rest = rows(15, 60, 0.0, 0.5, 0);
  full.insert(full.end(), rest.begin(), rest.end());
  const auto slow = rows(0, 100, 0, 0, 0);
  const std::string path = freshDir("grid") + "/comparison.csv";
  const ComparisonResult r = writeComparisonCsv(full, slow, kEps, path);
  EXPECT_EQ(r.rows, 55);
  EXPECT_EQ(r.unmatched_slow, 45);
  EXPECT_EQ(r.unmatched_full, 0);
  EXPECT_NEAR(r.max_abs_dA[1], 0.5, 1e-12);
  EXPECT_EQ(readLines(path).size(), 56u);
}

TEST(Compare, GridIndexSurvivesTheCsvPrecision) {
  for (long k : {0L, 1L, 7L, 12345L, 999999L, 20000000L}) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", envelopeTau(0.073, k));  // as formatEnvelopeRow
    EXPECT_EQ(envelopeIndex(0.073, std::stod(buf)), k);
  }
}

TEST(Compare, FromFilesEqualsInMemory) {
  const std::string dir = freshDir("files");
  const auto slow = rows(0, 300, 0, 0, 0);
  const auto full = rows(3, 300, 0.03, 0.01, 2 * kPi + 0.2);
  for (const auto& [name, rs] : {std::pair{"full", &full}, std::pair{"slow", &slow}}) {
    std::ofstream out(dir + "/envelope_" + name + ".csv");
    out << envelopeHeader(2) << "\n";
    for (const auto& r : *rs) out << formatEnvelopeRow(r) << "\n";
  }
  const ComparisonResult a = writeComparisonCsv(full, slow, kEps, dir + "/a.csv");
  const ComparisonResult b = compareEnvelopeFiles(dir + "/envelope_full.csv",
                                                  dir + "/envelope_slow.csv", kEps, dir + "/b.csv");
  EXPECT_EQ(a.rows, 297);
  EXPECT_EQ(b.rows, a.rows);
  EXPECT_EQ(b.unmatched_slow, 3);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(b.max_abs_dA[i], a.max_abs_dA[i], 1e-10);
  EXPECT_NEAR(b.max_abs_dpsi[0], 0.2, 1e-9);
  EXPECT_EQ(readLines(dir + "/a.csv").size(), readLines(dir + "/b.csv").size());
  const nlohmann::json j = comparisonJson(b);
  EXPECT_EQ(j["max_abs_dA"].size(), 2u);
  EXPECT_EQ(j["rows"], 297);
}

TEST(Compare, NothingMatchedGivesNullMaxima) {
  const std::string dir = freshDir("none");
  const ComparisonResult r =
      writeComparisonCsv(rows(0, 5, 0, 0, 0), rows(10, 15, 0, 0, 0), kEps, dir + "/c.csv");
  EXPECT_EQ(r.rows, 0);
  const nlohmann::json j = comparisonJson(r);
  EXPECT_TRUE(j["max_abs_dA"][0].is_null());
  EXPECT_TRUE(j["max_abs_dpsi"][0].is_null());
}

TEST(Compare, MalformedEnvelopeFileIsReportedWithItsLine) {
  const std::string dir = freshDir("bad");
  {
    std::ofstream out(dir + "/e.csv");
    out << "tau,A_1,A_2,psi_2\n0.1,1,1,0\n0.2,1,oops,0\n";
  }
  EnvelopeCsvReader reader(dir + "/e.csv");
  EnvelopeRow r;
  EXPECT_TRUE(reader.next(r));
  try {
    reader.next(r);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("e.csv:3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace metrosync
