// Issue 39: no non-finite number in any output of a run that exits 0. A cell with no value is
// empty (it was `nan`); a non-finite number on its way into a file is a failure (exit 3) naming
// the file, the row and the column (sim/record/finite_check.h, tools/report/json_file.h). Every
// command's files are scanned here by a reader of their own, not by the writers' check; on main
// `continue` wrote nan into branches.csv's weight on every run and a sweep of a rig with
// mu_static wrote s = nan into regimes.csv.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "sim/record/atomic_file.h"
#include "sim/record/finite_check.h"
#include "tests/hostile/hostile_support.h"
#include "tools/report/json_file.h"
#include "tools/report/output_dir.h"
#include "tools/report/outputs.h"

namespace metrosync::hostile {
namespace {

namespace fs = std::filesystem;
using testing_support::scratchDir;
using testing_support::slurp;

// "FILE row R column C: CELL" for every cell of a CSV text that spells a non-finite number in any
// of the ways printf, iostreams and Python write one.
std::vector<std::string> nonFiniteCells(const std::string& file, const std::string& text) {
  static const std::regex bad(R"(^\s*[-+]?(nan|inf|infinity)(\(.*\))?\s*$)", std::regex::icase);
  std::vector<std::string> found;
  std::istringstream lines(text);
  std::string line;
  for (long row = 0; std::getline(lines, line); ++row) {
    std::stringstream cells(line);
    std::string cell;
    for (int col = 1; std::getline(cells, cell, ','); ++col)
      if (row > 0 && std::regex_match(cell, bad))
        found.push_back(file + " row " + std::to_string(row) + " column " + std::to_string(col) +
                        ": " + cell);
  }
  return found;
}

// Every CSV and JSON file under `dir`: no non-finite cell, every JSON file parses (JSON has no
// NaN: a non-finite number could only have become null, which the writers refuse).
void expectOnlyFiniteNumbers(const std::string& dir, const std::string& what) {
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".csv" && ext != ".json")) continue;
    ++files;
    const std::string text = slurp(e.path().string());
    for (const std::string& f : nonFiniteCells(e.path().filename().string(), text))
      ADD_FAILURE() << what << ": " << f;
    if (ext == ".json") {
      EXPECT_TRUE(nlohmann::json::accept(text)) << what << ": " << e.path();
    }
  }
  EXPECT_GT(files, 0) << what << ": no file in " << dir;
}

struct Command {
  std::string name, args;
};

// Every command that writes files, on shipped rigs, short. The sweep's rig has mu_static = mu
// (s had no value: nan) and one point made to fail (its numbers have no value: empty).
TEST(FiniteOutputs, EveryCommandWritesOnlyFiniteNumbers) {
  const std::string d = scratchDir("finite", "commands", true);
  const std::string map = rigPath("experiment-map.yaml");
  const std::string fast = " -q --no-plot --set simulation.tau=20";
  const std::vector<Command> commands = {
      {"run", "run --set simulation.duration=3 -q --no-plot"},
      {"run-slow", "run " + rigPath("experiment-scaled.yaml") + " --model slow" + fast},
      {"run-network",
       "run " + rigPath("two-swings.yaml") + " --set simulation.duration=1 -q --no-plot"},
      {"compare",
       "compare " + rigPath("experiment-scaled.yaml") + " -q --no-plot --set simulation.tau=5"},
      {"sweep", "sweep " + map +
                    " --vary metronomes.1.alpha=0:0.2:3 --set platform.friction.mu_static=0.03283" +
                    fast},
      {"sweep-full", "sweep " + map +
                         " --model full --vary platform.friction.mu=0:0.05:3 -q --no-plot --set "
                         "simulation.tau=2 --keep envelope"},
      {"basin", "basin " + map + " --random metronomes.0.start.phi=0:2pi --samples 4" + fast},
      {"continue", "continue " + rigPath("paper/f4.4-alpha4.yaml") +
                       " --param metronomes.1.alpha --from 3 --to 4 -q"},
      {"continue-mu0", "continue " + map + " --param platform.friction.mu --from 0.05 --to 0 -q"},
      {"continue-fold", "continue " + rigPath("paper/f4.4-alpha4.yaml") +
                            " --param metronomes.1.alpha --from 3 --to 4 -q"
                            " --fold platform.friction.mu --to2 0.5"},
      {"continue-full",
       "continue " + rigPath("paper/f4.3-mu0.2.yaml") +
           " --model full --param platform.friction.mu --to 0.25 --max-points 3 -q"},
  };
  for (const Command& c : commands) {
    const std::string out = d + "/" + c.name;
    testing_support::RunIn in;
    if (c.name == "sweep") in.env = "METROSYNC_SWEEP_FAIL_AT=1";  // metrosync-faults
    const CommandResult r = runMetrosync(c.args + " --out " + shellQuote(out), in);
    ASSERT_EQ(r.code, 0) << c.args << "\n" << r.err;
    expectOnlyFiniteNumbers(out, c.name);
  }
  // the failed point's row: its numbers empty, its message there
  const auto rows = testing_support::csvRows(d + "/sweep/regimes.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[2][1], "failed");
  EXPECT_EQ(rows[2][2], "");  // A_1
  // s = |Z| / mu with mu_static = mu: the Coulomb value, as without mu_static
  const std::size_t s_col = 6;
  ASSERT_EQ(rows[0][s_col], "s");
  EXPECT_NE(rows[1][s_col], "");
  // sweep-point and merge of that sweep, and scale's JSON on stdout
  ASSERT_EQ(runMetrosync("sweep-point " + shellQuote(d + "/sweep-full") + " 2 -q --no-plot --out " +
                         shellQuote(d + "/point"))
                .code,
            0);
  expectOnlyFiniteNumbers(d + "/point", "sweep-point");
  ASSERT_EQ(
      runMetrosync("merge " + shellQuote(d + "/sweep") + " -q --out " + shellQuote(d + "/merged"))
          .code,
      0);
  expectOnlyFiniteNumbers(d + "/merged", "merge");
  const CommandResult scale = runMetrosync("scale --json");
  ASSERT_EQ(scale.code, 0) << scale.err;
  EXPECT_TRUE(nlohmann::json::accept(scale.out));
}

// fit and measure on a run's own trajectory (fit reads it as is, docs/fit.md).
TEST(FiniteOutputs, FitWritesOnlyFiniteNumbers) {
  const std::string d = scratchDir("finite", "fit", true);
  ASSERT_EQ(
      runMetrosync("run --set simulation.duration=2 -q --no-plot --out " + shellQuote(d + "/data"))
          .code,
      0);
  const CommandResult r = runMetrosync(
      "fit " + rigPath("experiment.yaml") + " " + shellQuote(d + "/data/trajectory.csv") +
      " --free platform.friction.mu --local -q --no-plot --out " + shellQuote(d + "/fit"));
  ASSERT_EQ(r.code, 0) << r.err;
  expectOnlyFiniteNumbers(d + "/fit", "fit");
}

// ---- the check itself --------------------------------------------------------------------------

TEST(FiniteOutputs, TheCheckKnowsEverySpellingOfANonFiniteNumber) {
  for (const char* bad : {"nan", "NaN", "-nan", "+nan", "inf", "-inf", "+inf", "INF", "Infinity",
                          "-infinity", "nan(0x8000)"})
    EXPECT_TRUE(isNonFiniteText(bad)) << bad;
  for (const char* fine : {"", "0", "-1.5e+300", "in-phase", "n", "info", "nano", "stuck", "i",
                           "\"nan\"", "suppressed:1", "1e308", "-0"})
    EXPECT_FALSE(isNonFiniteText(fine)) << fine;
}

// The run's own rows are checked as numbers where they are formatted, not read again as text
// (tools/report/deferred_rows.h): a non-finite double in the second block of trajectory rows, or
// in an event's state, is still refused by file, row and column, and no file reaches its name.
TEST(FiniteOutputs, ARunsRowWithANonFiniteNumberIsRefusedByName) {
  const std::string d = scratchDir("finite", "rows", true);
  RunFilesOptions o;
  o.n_metronomes = 2;
  o.tau_end = 10;
  o.events = true;
  const std::vector<double> fine = {0.5, 1e-3, 0, 0.25, -1.5, 0, 0, 1};
  for (const double bad : {HUGE_VAL, -HUGE_VAL, std::nan("")}) {
    const std::string text = bad != bad ? "nan" : (bad > 0 ? "inf" : "-inf");
    for (const bool in_event : {false, true}) {
      OutputDir dir(d + "/" + text + (in_event ? "-event" : "-row"));
      {
        FileSink sink(dir, o);
        for (int k = 0; k < 300; ++k) sink.trajectoryRow(fine);  // the first block passes
        for (int k = 0; k < 3; ++k) sink.eventRecord("tick", 0, fine, fine);
        std::vector<double> row = fine;
        row[4] = bad;  // thetadot_1
        if (in_event)
          sink.eventRecord("slip", -1, fine, row);  // thetadot_1_after
        else
          sink.trajectoryRow(row);
        try {
          sink.commit();
          ADD_FAILURE() << "accepted " << text;
        } catch (const NonFiniteOutput& e) {
          const std::string want =
              in_event ? dir.file("events.csv") + ": row 4, column thetadot_1_after: "
                       : dir.file("trajectory.csv") + ": row 301, column thetadot_1: ";
          EXPECT_EQ(std::string(e.what()),
                    want + text + " is not a finite number (a cell with no value is empty)");
        }
      }
      EXPECT_FALSE(fs::exists(dir.file("trajectory.csv"))) << text;
      EXPECT_FALSE(fs::exists(dir.file("events.csv"))) << text;
    }
  }
}

// A row with a non-finite cell: refused naming file, row and column (the header's name); the
// file never reaches its final name; a quoted cell is text.
TEST(FiniteOutputs, ACsvRowWithANonFiniteCellIsRefusedByName) {
  const std::string d = scratchDir("finite", "csv", true);
  {
    AtomicFile f(d + "/x.csv");
    f.writeLine("t,A_1,message");
    f.writeLine("0,1.5,\"ends in nan, inf\"");
    f.write("0.5,2,\n1,");
    try {
      f.write("-inf,why\n");
      ADD_FAILURE() << "accepted -inf";
    } catch (const NonFiniteOutput& e) {
      EXPECT_EQ(std::string(e.what()), d + "/x.csv: row 3, column A_1: -inf is not a finite number "
                                           "(a cell with no value is empty)");
    }
  }
  EXPECT_FALSE(fs::exists(d + "/x.csv"));
  // not a CSV: not checked (a plot's data for gnuplot says nan for a gap)
  writeFileAtomically(d + "/y.dat", "t nan\n1 nan\n");
  EXPECT_TRUE(fs::exists(d + "/y.dat"));
}

TEST(FiniteOutputs, AJsonNumberThatIsNotFiniteIsRefusedWithItsPlace) {
  nlohmann::json j = {{"final", {{"A", {1.0, std::nan("")}}}}, {"absent", nullptr}};
  try {
    checkFiniteJson("summary.json", j);
    ADD_FAILURE() << "accepted NaN";
  } catch (const NonFiniteOutput& e) {
    EXPECT_EQ(std::string(e.what()),
              "summary.json: /final/A/1 = nan is not a finite number (a value left out is null)");
  }
  j["final"]["A"][1] = 2.0;
  EXPECT_NO_THROW(checkFiniteJson("summary.json", j));
  j["x"] = HUGE_VAL;
  EXPECT_THROW(checkFiniteJson("summary.json", j), NonFiniteOutput);
}

}  // namespace
}  // namespace metrosync::hostile
