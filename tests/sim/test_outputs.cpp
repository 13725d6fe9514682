// Output files (SPEC 3): written whole or not at all, streamed, and the summary's keys.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "sim/record/envelope_csv.h"
#include "sim/record/finite_check.h"
#include "tools/report/outputs.h"
#include "tools/report/run_columns.h"

namespace metrosync {
namespace {

namespace fs = std::filesystem;

// A fresh, empty directory per test.
std::string freshDir(const std::string& name) {
  const std::string d =
      ::testing::TempDir() + "/metrosync_outputs_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(d);
  return d;
}

std::vector<std::string> listDir(const std::string& d) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(d)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string l;
  while (std::getline(in, l)) lines.push_back(l);
  return lines;
}

EnvelopeRow row2(double tau, double a1, double a2, double psi) {
  return {tau, {a1, a2}, {psi}};
}

TEST(AtomicFile, WithoutCommitLeavesNothing) {
  OutputDir dir(freshDir("nocommit"));
  {
    AtomicFile f(dir.file("data.csv"));
    f.writeLine("a,b");
    f.writeLine("1,2");
    EXPECT_TRUE(fs::exists(f.tempPath()));
    EXPECT_FALSE(fs::exists(dir.file("data.csv")));
  }
  EXPECT_TRUE(listDir(dir.path()).empty());
}

TEST(AtomicFile, CommitRenamesAndKeepsEveryLine) {
  OutputDir dir(freshDir("commit"));
  AtomicFile f(dir.file("data.csv"));
  for (int k = 0; k < 50000; ++k) f.writeLine(std::to_string(k));
  // the temporary name is hidden and says it is partial
  const std::string temp = fs::path(f.tempPath()).filename().string();
  EXPECT_EQ(temp[0], '.');
  EXPECT_NE(temp.find(".part"), std::string::npos);
  f.commit();
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"data.csv"});
  const auto lines = readLines(dir.file("data.csv"));
  ASSERT_EQ(lines.size(), 50000u);
  EXPECT_EQ(lines.front(), "0");
  EXPECT_EQ(lines.back(), "49999");
}

TEST(AtomicFile, ReplacesAnOlderFileOnlyOnCommit) {
  OutputDir dir(freshDir("replace"));
  writeFileAtomically(dir.file("summary.json"), "old\n");
  {
    AtomicFile f(dir.file("summary.json"));
    f.write("new\n");
    EXPECT_EQ(readLines(dir.file("summary.json")), std::vector<std::string>{"old"});
    f.commit();
  }
  EXPECT_EQ(readLines(dir.file("summary.json")), std::vector<std::string>{"new"});
}

// CommitBatch: the files of a run made durable together. Until finish() every final name keeps
// its old contents (or is absent); after it, every file is new and whole and no .part is left.
TEST(CommitBatch, RenamesNothingUntilFinishThenEverythingInOrder) {
  OutputDir dir(freshDir("batch"));
  writeFileAtomically(dir.file("summary.json"), "old\n");
  CommitBatch batch;
  AtomicFile a(dir.file("trajectory.csv"));
  for (int k = 0; k < 20000; ++k) a.writeLine(std::to_string(k));
  a.commit();
  writeFileAtomically(dir.file("summary.json"), "new\n");
  // committed, not yet renamed: the old summary, no trajectory, two temporary files
  EXPECT_EQ(readLines(dir.file("summary.json")), std::vector<std::string>{"old"});
  EXPECT_FALSE(fs::exists(dir.file("trajectory.csv")));
  EXPECT_EQ(listDir(dir.path()).size(), 3u);
  batch.finish();
  EXPECT_EQ(listDir(dir.path()), (std::vector<std::string>{"summary.json", "trajectory.csv"}));
  EXPECT_EQ(readLines(dir.file("summary.json")), std::vector<std::string>{"new"});
  const auto lines = readLines(dir.file("trajectory.csv"));
  ASSERT_EQ(lines.size(), 20000u);
  EXPECT_EQ(lines.back(), "19999");
  // the batch is over: a later commit renames at once
  writeFileAtomically(dir.file("late.txt"), "x\n");
  EXPECT_TRUE(fs::exists(dir.file("late.txt")));
}

TEST(CommitBatch, WithoutFinishWritesNothingAndKeepsTheOldFiles) {
  OutputDir dir(freshDir("batch_abort"));
  writeFileAtomically(dir.file("summary.json"), "old\n");
  {
    CommitBatch batch;
    writeFileAtomically(dir.file("envelope.csv"), "1,2\n");
    writeFileAtomically(dir.file("summary.json"), "new\n");
  }  // an exception before finish(): nothing of the batch is written
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"summary.json"});
  EXPECT_EQ(readLines(dir.file("summary.json")), std::vector<std::string>{"old"});
}

TEST(CommitBatch, BelongsToItsThreadOnly) {
  OutputDir dir(freshDir("batch_thread"));
  CommitBatch batch;
  std::thread([&] { writeFileAtomically(dir.file("other.txt"), "x\n"); }).join();
  EXPECT_TRUE(fs::exists(dir.file("other.txt")));  // another thread's commit is not queued
  writeFileAtomically(dir.file("mine.txt"), "y\n");
  EXPECT_FALSE(fs::exists(dir.file("mine.txt")));
  batch.finish();
  EXPECT_EQ(readLines(dir.file("mine.txt")), std::vector<std::string>{"y"});
}

TEST(OutputDir, CreatesParentsAndRefusesAFile) {
  const std::string base = freshDir("parents");
  OutputDir dir(base + "/a/b/c/");
  EXPECT_TRUE(fs::is_directory(base + "/a/b/c"));
  EXPECT_EQ(dir.path(), base + "/a/b/c");
  writeFileAtomically(base + "/plain", "x");
  EXPECT_THROW(OutputDir(base + "/plain"), std::runtime_error);
}

TEST(OutputDir, DefaultNameIsRunsRigCommand) {
  EXPECT_EQ(defaultOutputDir("wittner-pair", "run"), "runs/wittner-pair-run");
  EXPECT_EQ(defaultOutputDir("a b/../c", "compare"), "runs/a_b_.._c-compare");
  EXPECT_EQ(defaultOutputDir("..", "run"), "runs/rig-run");
  EXPECT_EQ(defaultOutputDir("", "run"), "runs/rig-run");
}

TEST(OutputDir, RemovesOnlyItsOwnStaleFiles) {
  OutputDir dir(freshDir("stale"));
  writeFileAtomically(dir.file("trajectory.csv"), "old");
  writeFileAtomically(dir.file("notes.txt"), "mine");
  // a temporary file of a dead process (pid 2^22 + 1 is above Linux's default pid_max)
  writeFileAtomically(dir.file(".envelope.csv.4194305.part"), "partial");
  writeFileAtomically(dir.file(".notes.txt.4194305.part"), "not ours");
  dir.removeStaleOutputs();
  EXPECT_EQ(listDir(dir.path()),
            (std::vector<std::string>{".notes.txt.4194305.part", "notes.txt"}));
}

TEST(EnvelopeDecimator, BoundedEvenlySpacedAndEndsWithTheLastRow) {
  EnvelopeDecimator d(100);
  const long total = 123457;
  for (long k = 0; k < total; ++k) d.add(row2(static_cast<double>(k), 1, 1, 0));
  const auto rows = d.rows();
  EXPECT_LE(rows.size(), 201u);
  EXPECT_GE(rows.size(), 100u);
  EXPECT_EQ(rows.front().tau, 0.0);
  EXPECT_EQ(rows.back().tau, static_cast<double>(total - 1));
  const double stride = rows[1].tau - rows[0].tau;
  EXPECT_EQ(stride, static_cast<double>(d.stride()));
  for (size_t k = 1; k + 1 < rows.size(); ++k) EXPECT_EQ(rows[k].tau - rows[k - 1].tau, stride);
}

TEST(EnvelopeDecimator, KeepsEverythingWhenSmall) {
  EnvelopeDecimator d(100);
  for (int k = 0; k < 150; ++k) d.add(row2(k, 1, 1, 0));
  EXPECT_EQ(d.rows().size(), 150u);
}

RunFilesOptions twoMetronomes(double tau_end) {
  RunFilesOptions o;
  o.n_metronomes = 2;
  o.tau_end = tau_end;
  o.epsilon = 0.02;  // 5 fast periods = 0.63 in tau: the window is the last 10%
  o.max_plot_rows = 50;
  return o;
}

TEST(FileSink, DestroyedWithoutCommitLeavesNoFinalFile) {
  OutputDir dir(freshDir("sink_nocommit"));
  {
    FileSink sink(dir, twoMetronomes(10));
    sink.trajectoryRow({0, 0, 0, 0.1, 0, 0.2, 0, 0});
    sink.envelopeRow(row2(0.2, 1, 1, 0.5));
    EXPECT_FALSE(fs::exists(dir.file("trajectory.csv")));
    EXPECT_FALSE(fs::exists(dir.file("envelope.csv")));
  }
  EXPECT_TRUE(listDir(dir.path()).empty());
}

TEST(FileSink, CommittedFilesHaveTheHeadersAndEveryRow) {
  OutputDir dir(freshDir("sink_commit"));
  FileSink sink(dir, twoMetronomes(100.1));  // window: tau >= 90.09
  const int n_traj = 20000, n_env = 500;
  for (int k = 0; k < n_traj; ++k)
    sink.trajectoryRow({0.01 * k, 1e-3 * k, 0, std::sin(0.01 * k), 0, 0, 0, (k % 3) - 1.0});
  for (int k = 0; k < n_env; ++k) sink.envelopeRow(row2(0.2 * k, 1.5, 1.4, 0.01 * k));
  sink.commit();
  const auto traj = readLines(dir.file("trajectory.csv"));
  ASSERT_EQ(traj.size(), static_cast<size_t>(n_traj + 1));
  EXPECT_EQ(traj[0], "t,x,xdot,theta_1,thetadot_1,theta_2,thetadot_2,platform");
  EXPECT_EQ(traj.back().substr(0, 6), "199.99");
  EXPECT_EQ(traj.back().substr(traj.back().size() - 2), ",0");  // 19999 % 3 - 1 = 0
  const auto env = readEnvelopeCsv(dir.file("envelope.csv"));
  ASSERT_EQ(env.size(), static_cast<size_t>(n_env));
  EXPECT_DOUBLE_EQ(env.back().psi[0], 0.01 * (n_env - 1));
  EXPECT_EQ(readLines(dir.file("envelope.csv"))[0], "tau,A_1,A_2,psi_2,r");
  EXPECT_EQ(sink.trajectoryRows(), n_traj);
  EXPECT_EQ(sink.envelopeRows(), n_env);
  // no temporary file left behind
  EXPECT_EQ(listDir(dir.path()), (std::vector<std::string>{"envelope.csv", "trajectory.csv"}));
  // what the summary and plots need was kept, in bounded memory
  EXPECT_EQ(sink.regimeWindow().rowsInWindow(), 49);  // tau = 90.2 .. 99.8
  EXPECT_LE(sink.plotRows().size(), 101u);
  EXPECT_DOUBLE_EQ(sink.plotRows().back().tau, 0.2 * (n_env - 1));
}

TEST(FileSink, SlowModelWritesNoTrajectory) {
  OutputDir dir(freshDir("sink_slow"));
  RunFilesOptions o = twoMetronomes(10);
  o.trajectory = false;
  o.envelope_name = "envelope_slow.csv";
  FileSink sink(dir, o);
  sink.trajectoryRow({0, 0, 0, 0, 0, 0, 0, 0});  // ignored
  sink.envelopeRow(row2(0.2, 1, 1, 0.5));
  sink.commit();
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"envelope_slow.csv"});
  EXPECT_EQ(sink.fileNames(), std::vector<std::string>{"envelope_slow.csv"});
}

TEST(FileSink, RejectsRowsOfTheWrongWidth) {
  OutputDir dir(freshDir("sink_width"));
  FileSink sink(dir, twoMetronomes(10));
  EXPECT_THROW(sink.trajectoryRow({0, 0, 0, 0.1, 0, 0}), std::logic_error);
  EXPECT_THROW(sink.envelopeRow({0.2, {1, 1, 1}, {0, 0}}), std::logic_error);
}

TEST(FileSink, AStopRequestInterruptsOnceAndKeepsTheRows) {
  OutputDir dir(freshDir("sink_stop"));
  FileSink sink(dir, twoMetronomes(10));
  sink.envelopeRow(row2(0.2, 1, 1, 0.5));
  FileSink::requestStop();
  EXPECT_THROW(sink.envelopeRow(row2(0.6, 1, 1, 0.5)), RunInterrupted);
  EXPECT_NO_THROW(sink.envelopeRow(row2(1.0, 1, 1, 0.5)));  // the engine's final row
  FileSink::clearStopRequest();
  sink.commit();
  EXPECT_EQ(readEnvelopeCsv(dir.file("envelope.csv")).size(), 3u);
}

TEST(Summary, HasTheSpecKeysAndFailureOnlyWhenIncomplete) {
  Rig rig;
  rig.name = "pair";
  rig.metronomes.resize(2);
  RunReport r;
  r.model = "full";
  r.engine = "simbody";
  r.integrator = "rk";
  r.accuracy = 1e-8;
  r.counts.steps = 12;
  r.counts.escapements = {3, 4};
  r.counts.stick_slip = 5;
  r.final_row = row2(7.5, 1.9, 1.8, 3.1);
  RegimeVerdict v;
  v.regime = Regime::Antiphase;
  nlohmann::json scaled = {{"epsilon", 0.073}};
  nlohmann::json j = runSummaryJson(rig, scaled, r, v);
  for (const char* key : {"model", "units", "regime", "final", "counts", "wall_seconds", "scaled",
                          "complete", "engine", "integrator", "accuracy", "rig", "version"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["regime"], "antiphase");
  EXPECT_EQ(j["units"], "physical");
  EXPECT_EQ(j["final"]["A"], (std::vector<double>{1.9, 1.8}));
  EXPECT_EQ(j["final"]["tau"], 7.5);
  EXPECT_EQ(j["counts"]["escapements"], (std::vector<long>{3, 4}));
  EXPECT_EQ(j["counts"]["stick_slip"], 5);
  EXPECT_EQ(j["scaled"]["epsilon"], 0.073);
  EXPECT_TRUE(j["complete"].get<bool>());
  EXPECT_FALSE(j.contains("failure"));
  EXPECT_FALSE(j.contains("energy"));

  r.complete = false;
  r.failure = "simulation failed at t = 3 s: non-finite state";
  r.has_ledger = true;
  r.ledger.initial_J = 1.0;
  r.ledger.final_J = 1.5;
  r.ledger.escapement_in_J = 2.0;
  r.ledger.damping_out_J = 1.0;
  r.ledger.friction_out_J = 0.25;
  j = runSummaryJson(rig, scaled, r, v);
  EXPECT_FALSE(j["complete"].get<bool>());
  EXPECT_EQ(j["failure"], r.failure);
  ASSERT_TRUE(j.contains("energy"));
  EXPECT_DOUBLE_EQ(j["energy"]["residual"].get<double>(), 0.5 - 0.75);
}

TEST(Summary, WrittenAtomicallyAndParses) {
  OutputDir dir(freshDir("summary"));
  // a non-finite number in a run that completed is a failure, and nothing is written (issue 39)
  EXPECT_THROW(writeSummary(dir, {{"model", "slow"}, {"x", NAN}}), NonFiniteOutput);
  EXPECT_FALSE(fs::exists(dir.file("summary.json")));
  // a failed run (exit 3 already) keeps its summary, the number it never reached null
  writeSummary(dir, {{"model", "slow"}, {"complete", false}, {"x", NAN}});
  std::ifstream in(dir.file("summary.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["model"], "slow");
  EXPECT_TRUE(j["x"].is_null());  // still valid JSON
}

// Without a folder (the Python module's run without out=): nothing is written, every row goes to
// the tap, the regime window is kept, and a stop request interrupts as with files.
TEST(FileSink, WithoutAFolderWritesNothingAndHandsEveryRowToTheTap) {
  const std::string dir = freshDir("sink_nofolder");
  fs::create_directories(dir);
  const std::filesystem::path cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  RunFilesOptions o = twoMetronomes(1.0);
  o.events = true;
  FileSink sink(o);
  RunColumns columns(o);
  sink.setTap(&columns);
  sink.trajectoryRow({0, 0, 0, 0.1, 0, 0.2, 0, 0});
  sink.trajectoryRow({0.5, 1e-3, 0, 0.3, 0.1, 0.2, 0, 1});
  sink.eventRecord("tick", 1, {0.5, 0, 0, 0, 0, 0, 0, 0}, {0.5, 1, 2, 3, 4, 5, 6, 1});
  sink.envelopeRow(row2(0.95, 1.5, 1.4, 0.5));
  FileSink::requestStop();
  EXPECT_THROW(sink.envelopeRow(row2(0.97, 1.5, 1.4, 0.5)), RunInterrupted);
  FileSink::clearStopRequest();
  sink.commit();
  std::filesystem::current_path(cwd);
  EXPECT_TRUE(listDir(dir).empty());
  EXPECT_TRUE(sink.fileNames().empty());
  EXPECT_EQ(sink.regimeWindow().rowsInWindow(), 2);
  EXPECT_EQ(columns.trajectory.rows(), 2u);
  EXPECT_EQ(columns.trajectory.values[8 + 1], 1e-3);  // row 1, x
  ASSERT_EQ(columns.envelope.rows(), 2u);  // the interrupting row too, as a file keeps it
  EXPECT_EQ(columns.envelope.names, (std::vector<std::string>{"tau", "A_1", "A_2", "psi_2", "r"}));
  EXPECT_EQ(columns.envelope.values[4], orderParameter({1.5, 1.4}, {0.5}));
  ASSERT_EQ(columns.events.rows(), 1u);
  EXPECT_EQ(columns.event_kinds, std::vector<std::string>{"tick"});
  EXPECT_EQ(columns.event_who, std::vector<std::string>{"2"});
  EXPECT_EQ(columns.events.values[1], 0.02 * 0.5);  // tau = epsilon t (scaled: time unit 1)
}

// With a folder and a tap: the files print the tap's numbers, to 12 digits (tau to 10).
TEST(RunColumns, HoldTheNumbersTheFilesPrint) {
  OutputDir dir(freshDir("sink_tap"));
  RunFilesOptions o = twoMetronomes(10);
  o.seconds = true;
  o.time_unit = 0.047;
  FileSink sink(dir, o);
  RunColumns columns(o);
  sink.setTap(&columns);
  for (int k = 0; k < 50; ++k) {
    sink.trajectoryRow({0.1 * k, 1e-4 * std::sin(k), 0, std::sin(0.3 * k) / 3, 0, 0.5, 0, 0});
    sink.envelopeRow(row2(0.2 * k + 1.0 / 3, 1.5 + 1e-3 * k, 1.4, 0.01 * k + 1.0 / 7));
  }
  sink.commit();
  auto printed = [](const ColumnTable& t, size_t row, bool tau10) {
    std::string line;
    for (size_t c = 0; c < t.names.size(); ++c) {
      char buf[40];
      std::snprintf(buf, sizeof buf, c == 0 && tau10 ? "%.10g" : "%.12g",
                    t.values[row * t.names.size() + c]);
      line += (c ? "," : "") + std::string(buf);
    }
    return line;
  };
  const auto env = readLines(dir.file("envelope.csv"));
  const auto traj = readLines(dir.file("trajectory.csv"));
  ASSERT_EQ(env.size(), 51u);
  ASSERT_EQ(traj.size(), 51u);
  EXPECT_EQ(env[0], "tau,A_1,A_2,psi_2,r,t_s");
  for (size_t k = 0; k < 50; ++k) {
    EXPECT_EQ(printed(columns.envelope, k, true), env[k + 1]);
    EXPECT_EQ(printed(columns.trajectory, k, false), traj[k + 1]);
  }
}

}  // namespace
}  // namespace metrosync
