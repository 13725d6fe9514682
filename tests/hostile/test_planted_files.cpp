// Issue 29: a shared output folder in which someone planted symbolic links or FIFOs. metrosync
// never writes through a link (the lock, the temporaries of every output, the files a --resume
// appends to), never waits on a FIFO, and leaves the victim file as it was.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "sim/record/atomic_file.h"
#include "sim/record/safe_open.h"
#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::scratchDir;
using testing_support::slurp;

const std::string kVictimText = "precious: not metrosync's\n";

std::string makeVictim(const std::string& dir) {
  const std::string victim = dir + "/victim.txt";
  std::ofstream(victim) << kVictimText;
  return victim;
}

bool isLink(const std::string& path) {
  return fs::is_symlink(fs::symlink_status(path));
}

// `sh -c 'ln -s VICTIM OUT/.NAME.$$.part ...; exec metrosync ARGS'`: the shell's pid is the
// command's, so the links sit at the exact temporary names the command will choose first.
CommandResult runWithPlantedTemporaries(const std::string& args, const std::string& out,
                                        const std::string& victim,
                                        const std::vector<std::string>& names) {
  std::string plant;
  for (const auto& n : names)
    plant += "ln -s " + shellQuote(victim) + " " + shellQuote(out) + "/." + n + ".$$.part && ";
  return testing_support::runCommand("sh -c " +
                                     shellQuote(plant + "exec " + shellQuote(METROSYNC_BINARY) +
                                                " " + args + " --out " + shellQuote(out)));
}

TEST(PlantedFiles, ALinkAtTheLockIsNotWrittenThrough) {
  const std::string d = scratchDir("planted", "lock", true);
  const std::string out = d + "/out", victim = makeVictim(d);
  fs::create_directories(out);
  fs::create_symlink(victim, out + "/.metrosync.lock");
  const CommandResult r =
      runLimited("sweep --vary platform.friction.mu=0.01:0.3:2 -q --no-plot", out);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(".metrosync.lock is a symbolic link"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(victim), kVictimText);
  EXPECT_FALSE(fs::exists(out + "/regimes.csv"));
}

TEST(PlantedFiles, ALinkAtARunsTemporariesIsNotWrittenThrough) {
  const std::string d = scratchDir("planted", "run", true);
  const std::string out = d + "/out", victim = makeVictim(d);
  fs::create_directories(out);
  const CommandResult r = runWithPlantedTemporaries(
      "run --set simulation.duration=2 -q", out, victim,
      {"summary.json", "envelope.csv", "trajectory.csv", "events.csv", "envelope.png",
       "envelope.png.dat", "envelope.png.gp", "envelope.png.log"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(victim), kVictimText);
  for (const char* f : {"summary.json", "envelope.csv", "trajectory.csv"}) {
    EXPECT_FALSE(isLink(out + "/" + f)) << f;
    EXPECT_TRUE(fs::is_regular_file(out + "/" + f)) << f;
  }
  EXPECT_NE(slurp(out + "/summary.json").find("\"complete\": true"), std::string::npos);
}

TEST(PlantedFiles, ALinkAtASweepsTemporariesIsNotWrittenThrough) {
  const std::string d = scratchDir("planted", "sweep", true);
  const std::string out = d + "/out", victim = makeVictim(d);
  fs::create_directories(out);
  const CommandResult r = runWithPlantedTemporaries(
      "sweep --vary platform.friction.mu=0.01:0.3:2 -q --no-plot --keep envelope", out, victim,
      {"sweep.json", "regimes.csv"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(victim), kVictimText);
  EXPECT_FALSE(isLink(out + "/sweep.json"));
  EXPECT_FALSE(isLink(out + "/regimes.csv"));
}

// --resume appends to regimes.csv, timings.csv and envelopes.csv.gz: a link or a FIFO put in
// place of one of them is refused (exit 2, named), not followed, not waited on.
TEST(PlantedFiles, ResumeRefusesALinkOrAFifoInPlaceOfItsFiles) {
  const std::string d = scratchDir("planted", "resume", true);
  const std::string out = d + "/out", victim = makeVictim(d);
  const std::string args =
      "sweep --vary platform.friction.mu=0.01:0.3:2 -q --no-plot --keep "
      "envelope --resume";
  ASSERT_EQ(runLimited(args, out).code, 0);
  for (const char* name : {"regimes.csv", "timings.csv", "envelopes.csv.gz"})
    for (bool fifo : {false, true}) {
      const std::string path = out + "/" + name, saved = d + "/saved";
      fs::rename(path, saved);
      if (fifo)
        ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
      else
        fs::create_symlink(victim, path);
      const CommandResult r = runLimited(args, out);  // 5 s: a wait on the FIFO is a kill
      EXPECT_EQ(r.code, 2) << name << (fifo ? " FIFO" : " link") << "\n" << r.err;
      EXPECT_NE(r.err.find(std::string(name) + " is a " + (fifo ? "FIFO" : "symbolic link")),
                std::string::npos)
          << r.err;
      EXPECT_EQ(slurp(victim), kVictimText);
      EXPECT_FALSE(fs::exists(out + "/.metrosync.lock")) << "the lock is left behind";
      fs::remove(path);
      fs::rename(saved, path);
    }
}

// The writer itself: a planted link at its first temporary name, another at the second.
TEST(PlantedFiles, AnAtomicFileNeverOpensAnExistingName) {
  const std::string d = scratchDir("planted", "atomic", true);
  const std::string victim = makeVictim(d), final_path = d + "/out.csv";
  const std::string first = temporaryPathFor(final_path);
  fs::create_symlink(victim, first);
  const std::string pid = std::to_string(::getpid());
  fs::create_symlink(victim, d + "/.out.csv.1." + pid + ".part");
  writeFileAtomically(final_path, "mine\n");
  EXPECT_EQ(slurp(victim), kVictimText);
  EXPECT_FALSE(isLink(final_path));
  EXPECT_EQ(slurp(final_path), "mine\n");
  EXPECT_TRUE(isLink(first));  // left alone, not removed and not followed
  // a hard link to the victim at an appended file's name
  fs::create_hard_link(victim, d + "/appended.csv");
  EXPECT_THROW(openOutputFile(d + "/appended.csv", false, true), UnsafeFileError);
  EXPECT_EQ(slurp(victim), kVictimText);
}

}  // namespace
}  // namespace metrosync::hostile
