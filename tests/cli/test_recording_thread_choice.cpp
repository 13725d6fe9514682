// Where `metrosync run` makes a single rig's rows does not change them: with a recording thread
// (which then also writes the files' text, tools/report/deferred_rows.h writeOnCallersThread),
// without one (the rows on the run's thread, the text on writer threads), everything on the run's
// thread, or as the engine judges by the run's length (sim/engines/direct/rig_recording.h), every
// file is the same to the byte. METROSYNC_RECORDING_THREAD (a bench's knob) takes never, always
// or inline, nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/common/run_metrosync.h"

namespace {

namespace ts = metrosync::testing_support;

std::string rig(const std::string& name) {
  return std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/bench/" + name + ".yaml";
}

}  // namespace

TEST(RecordingThreadChoice, EveryFileTheSameWhereverTheRowsAreMade) {
  // peer-n2: short (the engine judges no thread); n8: 202 fast periods of 8 (it judges one)
  for (const std::string name : {"peer-n2", "n8"}) {
    constexpr int kEnvs = 4;
    std::string files[kEnvs][3];
    const char* envs[kEnvs] = {"", "METROSYNC_RECORDING_THREAD=never",
                               "METROSYNC_RECORDING_THREAD=always",
                               "METROSYNC_RECORDING_THREAD=inline"};
    for (int e = 0; e < kEnvs; ++e) {
      const std::string out = ts::scratchDir("recthread", name + std::to_string(e));
      const auto r = ts::runMetrosync(
          "run " + ts::shellQuote(rig(name)) + " --quiet --no-plot --out " + ts::shellQuote(out),
          {"", envs[e]});
      ASSERT_EQ(r.code, 0) << envs[e] << r.err;
      const char* names[3] = {"trajectory.csv", "events.csv", "envelope.csv"};
      for (int f = 0; f < 3; ++f) files[e][f] = ts::slurp(out + "/" + names[f]);
      std::filesystem::remove_all(out);
    }
    EXPECT_GT(files[0][0].size(), 50000u) << name;  // rows enough for many blocks
    for (int e = 1; e < kEnvs; ++e)
      for (int f = 0; f < 3; ++f) EXPECT_EQ(files[e][f], files[0][f]) << name << " " << envs[e];
  }
}

TEST(RecordingThreadChoice, AnUnknownValueIsRefused) {
  const std::string out = ts::scratchDir("recthread", "bad");
  const auto r = ts::runMetrosync(
      "run " + ts::shellQuote(rig("peer-n2")) + " --quiet --no-plot --out " + ts::shellQuote(out),
      {"", "METROSYNC_RECORDING_THREAD=sometimes"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("METROSYNC_RECORDING_THREAD=sometimes"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/summary.json"));
  std::filesystem::remove_all(out);
}
