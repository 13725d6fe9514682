// Issue 29: every numeric option of every command parsed once, by one rule
// (tools/cli/number_option.h): NaN, infinities, 0 where a positive number is needed, numbers
// beyond their type and out-of-range values are refused with exit 2, the value quoted as typed,
// nothing written; no value silently becomes a default or is capped. A seeded fuzz pass runs
// every option through the real command line's parser.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "tests/hostile/hostile_support.h"
#include "tools/cli/animate.h"
#include "tools/cli/basin.h"
#include "tools/cli/command_line.h"
#include "tools/cli/continue.h"
#include "tools/cli/figures.h"
#include "tools/cli/fit.h"
#include "tools/cli/number_option.h"
#include "tools/cli/sweep.h"
#include "tools/cli/sweep_point.h"
#include "tools/cli/validate.h"
#include "yaml/utf8.h"

namespace metrosync::hostile {
namespace {

using testing_support::scratchDir;

// The issue's cases, end to end: exit 2, the value as typed, nothing written.
TEST(NumberOptions, TheIssuesCasesAreRefusedQuotingTheValueAsTyped) {
  const std::string map = shellQuote(sourceDir() + "/yaml/rigs/experiment-map.yaml");
  struct Case {
    std::string args, says;
  };
  const std::vector<Case> cases = {
      {"run --max-output nan", "--max-output nan: must be a number > 0"},
      {"run --max-output 0", "--max-output 0: must be a number > 0"},
      {"compare --max-output -inf", "--max-output -inf: must be a number > 0"},
      {"continue --param platform.friction.mu --to 0.5 --step 0", "--step 0: must be a number > 0"},
      {"continue --param platform.friction.mu --to 0.5 --step nan",
       "--step nan: must be a number > 0"},
      {"continue --param platform.friction.mu --to nan", "--to nan: must be a finite number"},
      {"continue --param platform.friction.mu --to 0.5 --from nan",
       "--from nan: must be a finite number"},
      {"continue --param platform.friction.mu --to 1e309", "--to 1e309: must be a finite number"},
      {"animate --fps nan", "--fps nan: must be a number > 0"},
      {"animate --speed 0", "--speed 0: must be a number > 0"},
      {"basin " + map + " --random metronomes.0.start.phi=0:1 --samples 18446744073709551617",
       "--samples 18446744073709551617: must be an integer from 1 to 10000000"},
      {"basin " + map +
           " --random metronomes.0.start.phi=0:1 --samples 5 --seed "
           "18446744073709551616",
       "--seed 18446744073709551616: must be an integer from 0 to 18446744073709551615"},
      {"basin " + map + " --random metronomes.0.start.phi=0:1 --samples 2.5",
       "--samples 2.5: must be an integer"},
      {"sweep --vary platform.friction.mu=0:1:2 --jobs 0", "--jobs 0: must be an integer from 1"},
      {"sweep --vary platform.friction.mu=0:1:2 --jobs 99999999999999999999",
       "--jobs 99999999999999999999: must be an integer from 1 to 4096"},
      {"continue --param platform.friction.mu --to 0.5 --max-points 1",
       "--max-points 1: must be an integer from 2"},
      {"measure --metronome 0", "--metronome 0: must be an integer from 1"},
      {"validate --jobs -1", "--jobs -1: must be an integer from 1"},
  };
  for (const Case& c : cases) {
    const std::string out = scratchDir("numbers", "case", false);
    const CommandResult r = runLimited(c.args, out);
    expectRefusedCleanly(r, out, c.args);
    EXPECT_NE(r.err.find("metrosync: error: " + c.says), std::string::npos) << c.args << "\n"
                                                                            << r.err;
  }
}

// A control character typed into a number comes back escaped, never raw.
TEST(NumberOptions, ControlCharactersInAValueAreEscaped) {
  const std::string out = scratchDir("numbers", "escape", false);
  const CommandResult r = runLimited("run --max-output $(printf '1\\033[2J\\007')", out);
  expectRefusedCleanly(r, out, "ESC");
  EXPECT_EQ(r.err.find('\033'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\007'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-output 1\\x1B[2J\\x07: must be"), std::string::npos) << r.err;
}

// ---- the fuzz pass -------------------------------------------------------------------------

// metrosync's whole command line (as tools/metrosync.cpp builds it), parsed without running.
struct CommandLine {
  CLI::App app;
  cli::Options opt;
  cli::SweepOptions sweep;
  cli::ValidateOptions validate;
  cli::FitOptions fit;
  cli::MeasureOptions measure;
  cli::FiguresOptions figures;
  cli::AnimateOptions animate;
  cli::BasinOptions basin;
  cli::SweepPointOptions point;
  CommandLine() {
    cli::configureApp(app);
    cli::addRigCommands(app, opt);
    cli::addSweepCommands(app, sweep);
    cli::addValidateCommand(app, validate);
    cli::addContinueCommand(app);
    cli::addFitCommand(app, fit);
    cli::addMeasureCommand(app, measure);
    cli::addFiguresCommand(app, figures);
    cli::addAnimateCommand(app, animate);
    cli::addBasinCommand(app, basin);
    cli::addSweepPointCommand(app, point);
  }
  // "" when the command line parses, else the parser's message
  std::string parse(std::vector<std::string> args) {
    std::vector<char*> argv = {const_cast<char*>("metrosync")};
    for (auto& a : args) argv.push_back(a.data());
    try {
      app.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const CLI::ParseError& e) {
      return e.what();
    }
    return "";
  }
};

// A hostile number: special words, signs, exponents at and beyond double's range, integers at
// and beyond 2^63 and 2^64, junk and control characters around digits.
std::string fuzzValue(std::mt19937_64& rng) {
  static const std::vector<std::string> words = {"nan",
                                                 "NaN",
                                                 "-nan",
                                                 "inf",
                                                 "-inf",
                                                 "infinity",
                                                 "0",
                                                 "-0",
                                                 "+0",
                                                 "0.0",
                                                 "1e309",
                                                 "-1e309",
                                                 "1e-400",
                                                 "4.9e-324",
                                                 "1.7976931348623157e308",
                                                 "9223372036854775807",
                                                 "9223372036854775808",
                                                 "18446744073709551615",
                                                 "18446744073709551616",
                                                 "-1",
                                                 "0x10",
                                                 "1,5",
                                                 " 1",
                                                 "1 ",
                                                 "",
                                                 "+",
                                                 "-",
                                                 "e5",
                                                 "1e",
                                                 "1.5.2",
                                                 "++1",
                                                 "+-1",
                                                 "1\x1b",
                                                 "\xc2\x85",
                                                 "1_000",
                                                 "5",
                                                 "2.5",
                                                 "100",
                                                 "4096",
                                                 "4097",
                                                 "1000000",
                                                 "3"};
  std::uniform_int_distribution<size_t> pick(0, words.size() - 1);
  std::string v = words[pick(rng)];
  if (rng() % 3 == 0) v += words[pick(rng)];  // two glued together
  return v;
}

TEST(NumberOptions, FuzzEveryNumericOptionOfEveryCommand) {
  struct Opt {
    std::vector<std::string> before;  // the command and what it needs besides the option
    std::string name;
    bool integer;
  };
  const std::vector<std::string> sweep = {"sweep", "--vary", "platform.friction.mu=0:1:2"};
  const std::vector<std::string> basin = {"basin", "--random", "a=0:1", "--samples", "3"};
  const std::vector<std::string> cont = {"continue", "--param", "k", "--to", "1"};
  const std::vector<Opt> options = {
      {{"run"}, "--max-output", false},
      {{"compare"}, "--max-output", false},
      {sweep, "--jobs", true},
      {sweep, "--basin-samples", true},
      {sweep, "--seed", true},
      {{"basin", "--random", "a=0:1"}, "--samples", true},
      {basin, "--seed", true},
      {basin, "--jobs", true},
      {{"continue", "--param", "k"}, "--to", false},
      {cont, "--from", false},
      {cont, "--step", false},
      {cont, "--max-points", true},
      {{"animate"}, "--fps", false},
      {{"animate"}, "--speed", false},
      {{"animate"}, "--from", false},
      {{"animate"}, "--to", false},
      {{"measure"}, "--metronome", true},
      {{"validate"}, "--jobs", true},
      {{"figures"}, "--jobs", true},
  };
  const char* seed_env = std::getenv("METROSYNC_FUZZ_SEED");
  std::mt19937_64 rng(seed_env ? std::strtoull(seed_env, nullptr, 10) : 29);
  const char* n_env = std::getenv("METROSYNC_FUZZ_OPTIONS");
  const long rounds = n_env ? std::atol(n_env) : 2000;
  long accepted = 0, refused = 0;
  for (long k = 0; k < rounds; ++k) {
    const Opt& o = options[rng() % options.size()];
    const std::string value = fuzzValue(rng);
    std::vector<std::string> args = o.before;
    args.push_back(o.name + "=" + value);  // "=": a value starting with '-' stays a value
    CommandLine cl;
    const std::string err = cl.parse(args);
    if (err.empty()) {
      ++accepted;
      // accepted only if it is a plain finite number, whole for an integer option
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      EXPECT_TRUE(!value.empty() && *end == '\0' && std::isfinite(v))
          << o.name << " accepted '" << value << "'";
      if (o.integer) {
        EXPECT_EQ(value.find_first_of(".eExX"), std::string::npos) << value;
      }
      continue;
    }
    ++refused;
    // refused by the rule: the option and the value as typed (escaped), never a capped number;
    // "--jobs=" (no value at all) is CLI11's own "missing"
    const std::string says =
        value.empty() ? o.name + ": 1 required" : o.name + " " + printable(value) + ": must be";
    EXPECT_NE(err.find(says), std::string::npos) << "'" << value << "': " << err;
  }
  EXPECT_GT(accepted, rounds / 20);
  EXPECT_GT(refused, rounds / 2);
}

TEST(NumberOptions, TheRuleItself) {
  using cli::parseIntegerText;
  using cli::parseNumberText;
  EXPECT_EQ(parseNumberText("--x", "2e10", cli::kPositive), 2e10);
  EXPECT_EQ(parseNumberText("--x", "+3", cli::kPositive), 3.0);
  EXPECT_EQ(parseNumberText("--x", "-0.5", cli::kAnyFinite), -0.5);
  EXPECT_EQ(parseIntegerText("--n", "4096", 1, 4096), 4096);
  EXPECT_EQ(cli::parseUnsignedText("--seed", "18446744073709551615"), UINT64_MAX);
  for (const char* bad : {"nan", "inf", "0", "-1", "1e400", "1x", "", "0x1p3"})
    EXPECT_THROW(parseNumberText("--x", bad, cli::kPositive), CLI::ValidationError) << bad;
  for (const char* bad : {"4097", "0", "1.0", "1e3", "9223372036854775808"})
    EXPECT_THROW(parseIntegerText("--n", bad, 1, 4096), CLI::ValidationError) << bad;
}

}  // namespace
}  // namespace metrosync::hostile
