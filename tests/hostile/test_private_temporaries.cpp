// Issue 29: gnuplot and ffmpeg never reopen a temporary file by a name someone else could replace.
// A stand-in for each program plays another user who can write the output folder: the moment the
// program starts, it replaces the temporary the image or video is written to (before: the
// hidden .NAME.<pid>.part next to it) by a link to a victim file, and a private folder by a link to
// a folder of such links, then runs the real program.
// The victim stays as it was and the plot or video is whole, in place, not a link.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "sim/record/private_dir.h"
#include "tests/hostile/hostile_support.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::RunIn;
using testing_support::scratchDir;
using testing_support::slurp;

const std::string kVictimText = "precious: not metrosync's\n";

// BIN/NAME: the attack on OUT (hidden entries whose name matches *PATTERN*, and every hidden
// folder), then `exec REAL "$@"`.
void writeAttacker(const std::string& bin, const std::string& name, const std::string& real,
                   const std::string& out, const std::string& victim, const std::string& pattern) {
  fs::create_directories(bin);
  const std::string path = bin + "/" + name;
  std::ofstream(path)
      << "#!/bin/sh\n"
      << "out=" << shellQuote(out) << "; victim=" << shellQuote(victim) << "\n"
      << "for f in \"$out\"/.[!.]*; do\n"
      << "  if [ -d \"$f\" ] && [ ! -L \"$f\" ]; then\n"
      << "    mv \"$f\" \"$f.moved\" && mkdir \"$f.evil\" &&\n"
      << "    for n in data out plot.gp log frames.mkv palette.png; do\n"
      << "      ln -s \"$victim\" \"$f.evil/$n\"; done && ln -s \"$f.evil\" \"$f\"\n"
      << "  else case \"$f\" in *" << pattern << "*)\n"
      << "    rm -f \"$f\" && ln -s \"$victim\" \"$f\";; esac; fi\n"
      << "done\n"
      << "exec " << shellQuote(real) << " \"$@\"\n";
  fs::permissions(path, fs::perms::owner_all);
}

// metrosync ARGS (its output in OUT) with the stand-in for /usr/bin/PROGRAM first on PATH.
struct Attacked {
  CommandResult r;
  std::string out, victim;
};
Attacked runAttacked(const std::string& program, const std::string& pattern,
                     const std::function<std::string(const std::string&)>& args) {
  Attacked a;
  const std::string d = scratchDir("private", program, true);
  const std::string bin = d + "/bin";
  a.out = d + "/out";
  a.victim = d + "/victim.txt";
  std::ofstream(a.victim) << kVictimText;
  fs::create_directories(a.out);
  writeAttacker(bin, program, "/usr/bin/" + program, a.out, a.victim, pattern);
  RunIn in;
  in.env = "PATH=" + shellQuote(bin + ":/usr/bin:/bin");
  a.r = runMetrosync(args(a.out), in);
  return a;
}

TEST(PrivateTemporaries, GnuplotsTemporariesCannotBeReplaced) {
  if (!fs::exists("/usr/bin/gnuplot")) GTEST_SKIP() << "no /usr/bin/gnuplot";
  const Attacked a = runAttacked("gnuplot", ".png.[0-9]", [](const std::string& out) {
    return "run --set simulation.duration=2 -q --out " + shellQuote(out);
  });
  EXPECT_EQ(a.r.code, 0) << a.r.err;
  EXPECT_EQ(slurp(a.victim), kVictimText) << "gnuplot wrote through a planted link";
  EXPECT_FALSE(fs::is_symlink(fs::symlink_status(a.out + "/envelope.png")));
  EXPECT_EQ(slurp(a.out + "/envelope.png").substr(0, 4), "\x89PNG") << a.r.err;
}

TEST(PrivateTemporaries, FfmpegsTemporariesCannotBeReplaced) {
  if (!fs::exists("/usr/bin/ffmpeg")) GTEST_SKIP() << "no /usr/bin/ffmpeg";
  const Attacked a = runAttacked("ffmpeg", ".mp4.[0-9]", [](const std::string& out) {
    return "animate --to 0.2 --fps 10 --out " + shellQuote(out + "/v.mp4");
  });
  if (a.r.code == 2 && a.r.err.find("Cairo") != std::string::npos) GTEST_SKIP() << "no Cairo";
  EXPECT_EQ(a.r.code, 0) << a.r.err;
  EXPECT_EQ(slurp(a.victim), kVictimText) << "ffmpeg wrote through a planted link";
  EXPECT_FALSE(fs::is_symlink(fs::symlink_status(a.out + "/v.mp4")));
  EXPECT_GT(slurp(a.out + "/v.mp4").size(), 100u) << a.r.err;
}

// The folder is the process's own, 0700, and reached through its descriptor after it was moved.
TEST(PrivateTemporaries, TheFolderIsPrivateAndFollowsItsDescriptor) {
  const std::string d = scratchDir("private", "folder", true);
  std::string moved;
  {
    PrivateDir tmp(d);
    struct stat st {};
    ASSERT_EQ(::lstat(tmp.path().c_str(), &st), 0);
    EXPECT_TRUE(S_ISDIR(st.st_mode));
    EXPECT_EQ(st.st_mode & 0777, 0700u);
    tmp.create("a", "one");
    moved = d + "/moved";
    fs::rename(tmp.path(), moved);                // someone renames it away ...
    fs::create_directory_symlink(d, tmp.path());  // ... and plants a link at its name
    tmp.create("b", "two");                       // still in the real folder
    EXPECT_EQ(slurp(moved + "/b"), "two");
    EXPECT_FALSE(fs::exists(d + "/b"));
    EXPECT_TRUE(tmp.publish("a", d + "/published"));
    EXPECT_EQ(slurp(d + "/published"), "one");
    fs::remove(tmp.path());
  }
  EXPECT_TRUE(fs::is_empty(moved)) << "the destructor removes what the folder held";
}

}  // namespace
}  // namespace metrosync::hostile
