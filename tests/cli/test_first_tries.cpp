// Issue 37, a new user's first tries: each defect found by reading README and docs only, end to
// end through the built binary (the plots' scripts in test_first_tries_plots.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/common/run_metrosync.h"

namespace {

namespace fs = std::filesystem;
using metrosync::testing_support::CommandResult;

const std::string kSource = METROSYNC_SOURCE_DIR;

CommandResult metrosync(const std::string& args, const std::string& cwd) {
  return metrosync::testing_support::runMetrosync(args, {cwd, ""});
}

std::string scratch(const std::string& name) {
  return metrosync::testing_support::scratchDir("first", name, true);
}

// Item 4: `run` then `run --model slow` in one folder: each model has its own default folder, so
// the second keeps the first's trajectory.csv and events.csv.
TEST(FirstTries, RunThenRunSlowKeepEachOthersFiles) {
  const std::string dir = scratch("models");
  const std::string short_run = " --set simulation.duration=2 --no-plot -q";
  ASSERT_EQ(metrosync("run" + short_run, dir).code, 0);
  ASSERT_EQ(metrosync("run --model slow" + short_run, dir).code, 0);
  const std::string full = dir + "/runs/experiment-run-";
  std::vector<std::string> folders;
  for (const auto& e : fs::directory_iterator(dir + "/runs"))
    folders.push_back(e.path().filename().string());
  ASSERT_EQ(folders.size(), 2u) << "one folder per model";
  int with_trajectory = 0;
  for (const std::string& f : folders) {
    const std::string d = dir + "/runs/" + f;
    std::ifstream in(d + "/summary.json");
    const auto s = nlohmann::json::parse(in);
    const bool slow = s["model"] == "slow";
    EXPECT_EQ(f.rfind(slow ? "experiment-run-slow-" : "experiment-run-", 0), 0u) << f;
    EXPECT_EQ(fs::exists(d + "/trajectory.csv"), !slow) << f;
    EXPECT_EQ(fs::exists(d + "/events.csv"), !slow) << f;
    with_trajectory += fs::exists(d + "/trajectory.csv");
  }
  EXPECT_EQ(with_trajectory, 1) << "the full model's files survive the slow run";
}

// Item 5: a key of the other units names the key to use instead, in --set and in --param.
TEST(FirstTries, AScaledKeyOnAPhysicalRigNamesThePhysicalKey) {
  const std::string dir = scratch("units");
  const CommandResult phi = metrosync("run --set metronomes.1.start.phi=3.54", dir);
  EXPECT_EQ(phi.code, 2);
  EXPECT_NE(phi.err.find("only with units: scaled"), std::string::npos) << phi.err;
  EXPECT_NE(phi.err.find("metronomes.1.start.angle (rad) and metronomes.1.start.rate"),
            std::string::npos)
      << phi.err;
  const CommandResult nu = metrosync("run --set 'metronomes.*.nu=0.6'", dir);
  EXPECT_EQ(nu.code, 2);
  EXPECT_NE(nu.err.find("metronomes.*.pendulum.damping (kg/s) or metronomes.*.pendulum.decay_rate"),
            std::string::npos)
      << nu.err;
  const CommandResult alpha = metrosync(
      "continue " + kSource + "/yaml/rigs/experiment.yaml --param metronomes.1.alpha --to 1", dir);
  EXPECT_EQ(alpha.code, 2);
  EXPECT_NE(alpha.err.find("metronomes.1.pendulum.length (m)"), std::string::npos) << alpha.err;
  EXPECT_FALSE(fs::exists(dir + "/runs")) << "nothing written";
}

// Item 6: a mistyped command is named, with the command it is closest to.
TEST(FirstTries, AMistypedCommandSaysWhichOneWasMeant) {
  const std::string dir = scratch("runn");
  const CommandResult r = metrosync("runn", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown command 'runn' (did you mean 'run'?)"), std::string::npos) << r.err;
  const CommandResult far = metrosync("frobnicate", dir);
  EXPECT_EQ(far.code, 2);
  EXPECT_NE(far.err.find("unknown command 'frobnicate' (the commands: run, compare"),
            std::string::npos)
      << far.err;
  EXPECT_EQ(metrosync("--version", dir).code, 0);  // options before a command are untouched
}

// Item 7 and the sensible ranges: a unit typed wrong runs with a warning naming the key, the
// value and the range; --strict refuses it (exit 2, nothing written); a hard rig still runs.
TEST(FirstTries, AUnitTypedWrongWarnsAndStrictRefusesIt) {
  const std::string dir = scratch("ranges");
  const std::string mm =
      "run --set metronomes.0.pendulum.length=22.5 --set simulation.duration=1 "
      "--no-plot -q --out mm";
  const CommandResult warned = metrosync(mm, dir);
  EXPECT_EQ(warned.code, 0) << warned.err;
  EXPECT_NE(warned.err.find("metrosync: warning: <default rig>: --set "
                            "metronomes.0.pendulum.length=22.5: metronomes.0.pendulum.length = "
                            "22.5 m: outside 0.005 .. 0.5 m"),
            std::string::npos)
      << warned.err;
  EXPECT_NE(warned.err.find("in millimetres?"), std::string::npos) << warned.err;
  const CommandResult board =
      metrosync("scale --set platform.mass=143.2", dir);  // grams for kilograms
  EXPECT_EQ(board.code, 0);
  EXPECT_NE(board.err.find("platform.mass = 143.2 kg: outside 0.01 .. 20 kg"), std::string::npos)
      << board.err;
  EXPECT_NE(board.err.find("in grams?"), std::string::npos) << board.err;

  const CommandResult strict =
      metrosync("run --strict --set metronomes.0.pendulum.length=22.5 --out strict", dir);
  EXPECT_EQ(strict.code, 2);
  EXPECT_NE(strict.err.find("metrosync: error: <default rig>: --set "
                            "metronomes.0.pendulum.length=22.5"),
            std::string::npos)
      << strict.err;
  EXPECT_FALSE(fs::exists(dir + "/strict")) << "nothing written";
  for (const char* cmd : {"sweep --vary platform.friction.mu=1e-3,2e-3",
                          "basin --random "
                          "metronomes.0.start.angle=0:0.5 --samples 2",
                          "continue --param "
                          "platform.friction.mu --to 1e-3"}) {
    const CommandResult r =
        metrosync(std::string(cmd) + " --strict --set platform.mass=143.2 --out s", dir);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find("platform.mass = 143.2 kg"), std::string::npos) << cmd << r.err;
  }
  EXPECT_FALSE(fs::exists(dir + "/s"));

  // the paper's own rig is inside every range: no warning at all
  const CommandResult paper =
      metrosync("run --set simulation.duration=1 --no-plot -q --out p", dir);
  EXPECT_EQ(paper.code, 0);
  EXPECT_EQ(paper.err.find("warning"), std::string::npos) << paper.err;
  // a deliberately extreme rig warns and still runs: hard/storm.yaml's 3e19 N/m spring ends in
  // its event storm (exit 3, the run's own verdict), not in a refusal (exit 2)
  const CommandResult hard =
      metrosync("run " + kSource + "/yaml/rigs/hard/storm.yaml --no-plot -q --out hard", dir);
  EXPECT_EQ(hard.code, 3) << hard.err;
  EXPECT_NE(hard.err.find("warning: " + kSource + "/yaml/rigs/hard/storm.yaml:12:"),
            std::string::npos)
      << hard.err;
  EXPECT_NE(hard.err.find("platform.spring.k = 3.0e19 N/m: outside 0.01 .. 10000 N/m"),
            std::string::npos)
      << hard.err;
}

// Item 8: --jobs 0 is refused by every command, as by sweep (issue 29's rule: no value stands
// for "the default").
TEST(FirstTries, JobsZeroIsRefusedByEveryCommand) {
  const std::string dir = scratch("jobs");
  for (const char* cmd : {"figures --quick --only f4.1", "validate --quick",
                          "sweep --vary platform.friction.mu=0:1:2",
                          "basin --random metronomes.0.start.angle=0:0.5 --samples 2"}) {
    const CommandResult r = metrosync(std::string(cmd) + " --jobs 0 --out j", dir);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find("--jobs"), std::string::npos) << cmd << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(dir + "/j"));
}

// Item 9: `run`'s "files:" line names every file written, summary.json included.
TEST(FirstTries, RunListsEveryFileItWrote) {
  const std::string dir = scratch("files");
  const CommandResult r = metrosync("run --set simulation.duration=1 --no-plot --out o", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::size_t at = r.out.find("files: o/ (");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string listed = r.out.substr(at);
  for (const auto& e : fs::directory_iterator(dir + "/o"))
    EXPECT_NE(listed.find(e.path().filename().string()), std::string::npos)
        << e.path().filename() << " not in: " << listed;
  EXPECT_NE(listed.find("summary.json"), std::string::npos);
}

// Item 9: `--vary KEY=V` with one value is a grid of one point along that key.
TEST(FirstTries, VaryTakesOneValue) {
  const std::string dir = scratch("vary1");
  const CommandResult s = metrosync("sweep " + kSource +
                                        "/yaml/rigs/experiment-map.yaml --vary "
                                        "platform.friction.mu=0.3 --set simulation.tau=20 "
                                        "--no-plot -q --out one",
                                    dir);
  ASSERT_EQ(s.code, 0) << s.err;
  const auto rows = metrosync::testing_support::csvRows(dir + "/one/regimes.csv");
  ASSERT_EQ(rows.size(), 2u) << "a header and one point";
  EXPECT_EQ(rows[0][0], "platform.friction.mu");
  EXPECT_EQ(rows[1][0], "0.3");
}

// Item 9: animate says how much motion the video shows, not "simulation 0.00 s".
TEST(FirstTries, AnimateSaysTheMotionItShows) {
  const std::string dir = scratch("animate");
  const CommandResult r = metrosync(
      "animate --set simulation.duration=1 --speed 0.5 --fps 10 --size 128x128 --out a.gif", dir);
  if (r.code == 2 &&
      (r.err.find("ffmpeg") != std::string::npos || r.err.find("Cairo") != std::string::npos))
    GTEST_SKIP() << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  // 1 s of motion at half speed: 20 frames at 10 fps, 2 s of video showing 1 s of motion
  EXPECT_NE(r.out.find("2.00 s of video showing 1 s of motion"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("simulation 0.00 s"), std::string::npos) << r.out;
}

}  // namespace
