// `sweep --keep envelope` and `sweep-point` (docs/sweep-points.md): the stored envelope of a point
// equals `run` of that point's rig bit for bit, sweep-point reproduces the point's regimes.csv
// row, an interrupted sweep resumed stores every point once, and bad input exits 2.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/common/run_metrosync.h"
#include "tools/report/envelope_store.h"

namespace {

namespace fs = std::filesystem;
using Result = metrosync::testing_support::CommandResult;
using metrosync::testing_support::shellQuote;
using metrosync::testing_support::slurp;

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("sweep-point", name, true);
}

Result metrosync(const std::string& args, const std::string& env = "") {
  return metrosync::testing_support::runMetrosync(args, {"", env});
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> v;
  std::stringstream ss(text);
  std::string l;
  while (std::getline(ss, l)) v.push_back(l);
  return v;
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> v;
  std::stringstream ss(line);
  std::string c;
  while (std::getline(ss, c, ',')) v.push_back(c);
  return v;
}

std::string pairRig(const std::string& dir) {
  return metrosync::testing_support::writePairRig(dir, 40);
}

const std::string kGrid =
    " --vary metronomes.0.start.phi=0,1.5,3 --vary platform.friction.mu=0.1,0.3 --model slow";

// point -> its lines of the store, decompressed by gzip(1) (not by the reader under test); a
// point counts with its #end line only. damaged: gzip may report the cut-off tail.
std::map<long, std::vector<std::string>> storeByGzip(const std::string& dir, bool damaged = false) {
  const std::string out = dir + "/store.txt";
  const std::string cmd = "gzip -dc " + shellQuote(dir + "/envelopes.csv.gz") + " > " + out +
                          (damaged ? " 2>/dev/null" : "");
  const int status = std::system(cmd.c_str());
  if (!damaged) {
    EXPECT_EQ(status, 0);
  }
  std::map<long, std::vector<std::string>> points, open;
  const std::vector<std::string> lines = splitLines(slurp(out));
  EXPECT_FALSE(lines.empty());
  if (lines.empty()) return points;
  EXPECT_EQ(lines.front(), "point,tau,A_1,A_2,psi_2,r");
  for (size_t k = 1; k < lines.size(); ++k) {
    const std::string& l = lines[k];
    if (l.rfind("#end,", 0) == 0) {
      const long g = std::stol(l.substr(5));
      if (static_cast<long>(open[g].size()) == std::stol(l.substr(l.find(',', 5) + 1)))
        points[g] = open[g];
      open.erase(g);
      continue;
    }
    const size_t comma = l.find(',');
    if (comma == std::string::npos || l.find_first_not_of("0123456789") != comma) continue;
    open[std::stol(l.substr(0, comma))].push_back(l.substr(comma + 1));
  }
  return points;
}

// regimes.csv: index -> cells, and the header
std::map<long, std::vector<std::string>> regimeRows(const std::string& dir,
                                                    std::vector<std::string>& header) {
  std::vector<std::string> lines = splitLines(slurp(dir + "/regimes.csv"));
  header = cells(lines.at(0));
  const size_t index_col = std::find(header.begin(), header.end(), "index") - header.begin();
  std::map<long, std::vector<std::string>> rows;
  for (size_t k = 1; k < lines.size(); ++k) {
    auto c = cells(lines[k]);
    rows[std::stol(c.at(index_col))] = c;
  }
  return rows;
}

// envelope.csv's rows (no header)
std::vector<std::string> envelopeRows(const std::string& dir) {
  std::vector<std::string> v = splitLines(slurp(dir + "/envelope.csv"));
  if (!v.empty()) v.erase(v.begin());
  return v;
}

TEST(SweepKeepEnvelope, StoredRowsEqualRunOfThePointsRigBitForBit) {
  const std::string d = scratch("roundtrip");
  const std::string rig = pairRig(d);
  const Result sw = metrosync("sweep " + shellQuote(rig) + kGrid +
                              " --jobs 2 -q --no-plot --keep envelope --out " + d + "/sw");
  ASSERT_EQ(sw.code, 0) << sw.err;
  const auto store = storeByGzip(d + "/sw");
  ASSERT_EQ(store.size(), 6u);
  std::vector<std::string> header;
  const auto rows = regimeRows(d + "/sw", header);
  ASSERT_EQ(rows.size(), 6u);
  // the reader agrees with gzip(1)
  EXPECT_EQ(metrosync::readEnvelopeStore(d + "/sw/envelopes.csv.gz"), store);
  for (long k : {0L, 3L, 5L}) {
    SCOPED_TRACE("point " + std::to_string(k));
    const auto& row = rows.at(k);
    const std::string sets =
        " --set " + header[0] + "=" + row[0] + " --set " + header[1] + "=" + row[1];
    const std::string out = d + "/run" + std::to_string(k);
    const Result run =
        metrosync("run " + shellQuote(rig) + " --model slow -q --no-plot" + sets + " --out " + out);
    ASSERT_EQ(run.code, 0) << run.err;
    const std::vector<std::string> expected = envelopeRows(out);
    ASSERT_GT(expected.size(), 20u);
    EXPECT_EQ(store.at(k), expected);
  }
  // a different point's rows differ (the comparison can fail)
  EXPECT_NE(store.at(0), store.at(5));
}

TEST(SweepPoint, ReproducesTheRegimesRowWithFullOutputs) {
  const std::string d = scratch("point");
  const std::string rig = pairRig(d);
  ASSERT_EQ(metrosync("sweep " + shellQuote(rig) + kGrid +
                      " --jobs 1 -q --no-plot --keep envelope --out " + d + "/sw")
                .code,
            0);
  std::vector<std::string> header;
  const auto rows = regimeRows(d + "/sw", header);
  const auto store = storeByGzip(d + "/sw");
  const size_t regime_col = std::find(header.begin(), header.end(), "regime") - header.begin();
  for (long k : {1L, 4L}) {
    SCOPED_TRACE("point " + std::to_string(k));
    const Result p = metrosync("sweep-point " + d + "/sw " + std::to_string(k));
    ASSERT_EQ(p.code, 0) << p.err;
    const std::string out = d + "/sw/point-" + std::to_string(k);
    ASSERT_TRUE(fs::exists(out + "/envelope.png")) << p.out;
    const auto summary = nlohmann::json::parse(slurp(out + "/summary.json"));
    EXPECT_EQ(summary["regime"].get<std::string>(), rows.at(k).at(regime_col));
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(summary["final"]["A"][i].get<double>(), std::stod(rows.at(k).at(3 + i)),
                  1e-9 * std::fabs(summary["final"]["A"][i].get<double>()) + 1e-300);
    EXPECT_EQ(envelopeRows(out), store.at(k));
  }
  // --out elsewhere
  ASSERT_EQ(metrosync("sweep-point " + d + "/sw 2 -q --no-plot --out " + d + "/p2").code, 0);
  EXPECT_EQ(envelopeRows(d + "/p2"), store.at(2));
}

TEST(SweepKeepEnvelope, AnInterruptedSweepResumedStoresEveryPointOnce) {
  const std::string d = scratch("resume");
  const std::string rig = pairRig(d);
  const std::string cmd =
      "sweep " + shellQuote(rig) + kGrid + " --jobs 1 -q --no-plot --keep envelope --out ";
  ASSERT_EQ(metrosync(cmd + d + "/whole").code, 0);
  const Result killed = metrosync(cmd + d + "/cut", "METROSYNC_SWEEP_STOP_AFTER=2");
  ASSERT_NE(killed.code, 0);
  // a damaged tail too: half a gzip member, as a kill in the middle of a write leaves
  {
    const std::string member = slurp(d + "/whole/envelopes.csv.gz");
    std::ofstream(d + "/cut/envelopes.csv.gz", std::ios::app | std::ios::binary)
        << member.substr(0, member.size() / 2);
  }
  // the two points written, and whatever the damaged half member decodes to
  EXPECT_GE(storeByGzip(d + "/cut", true).size(), 2u);
  const Result resumed = metrosync(cmd + d + "/cut --resume");
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  const auto whole = storeByGzip(d + "/whole"), cut = storeByGzip(d + "/cut");
  EXPECT_EQ(cut, whole);
  std::vector<std::string> lines = splitLines(slurp(d + "/cut/store.txt"));
  EXPECT_EQ(std::count_if(lines.begin(), lines.end(),
                          [](const std::string& l) { return l.rfind("#end,", 0) == 0; }),
            6);
}

TEST(SweepPoint, BadInputExitsTwo) {
  const std::string d = scratch("bad");
  const std::string rig = pairRig(d);
  ASSERT_EQ(metrosync("sweep " + shellQuote(rig) + kGrid + " -q --no-plot --out " + d + "/sw").code,
            0);
  const Result outside = metrosync("sweep-point " + d + "/sw 6");
  EXPECT_EQ(outside.code, 2);
  EXPECT_NE(outside.err.find("0..5"), std::string::npos) << outside.err;
  EXPECT_FALSE(fs::exists(d + "/sw/point-6"));
  const Result none = metrosync("sweep-point " + d + "/nothing 0");
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("sweep.json"), std::string::npos) << none.err;
  EXPECT_EQ(
      metrosync("sweep " + shellQuote(rig) + kGrid + " --keep trajectory --out " + d + "/k").code,
      2);
}

}  // namespace
