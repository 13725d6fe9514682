// docs/contract.md, the user contract in the repository (issue 37), held to the program: every key
// of the rig files' schemas, every output file a command's --help names, every regime label and
// every exit code the program has is named on the page. A key, a file or a label added without
// its line in the contract fails here.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "sim/analysis/regime.h"
#include "tests/common/run_metrosync.h"
#include "tools/cli/exit_codes.h"
#include "tools/report/output_dir.h"
#include "yaml/rig_schema.h"

namespace metrosync {
namespace {

using rigfile::Schema;

std::string page() {
  return testing_support::slurp(std::string(METROSYNC_SOURCE_DIR) + "/docs/contract.md");
}

// Every key path of a schema: maps' keys joined by '.', a list's elements as N.
void keyPaths(const Schema& s, const std::string& path, std::vector<std::string>& out) {
  if (s.kind == Schema::Kind::Map)
    for (const auto& kv : s.keys) {
      const std::string p = path.empty() ? kv.first : path + "." + kv.first;
      out.push_back(p);
      keyPaths(*kv.second, p, out);
    }
  if (s.kind == Schema::Kind::List) keyPaths(*s.item, path + ".N", out);
}

// A key written out in full (`metronomes.N.pendulum.mass`), or for the friction law's, a
// network's and a spring's keys, the key's own name in backticks beside its parent's.
bool named(const std::string& text, const std::string& path) {
  if (text.find("`" + path + "`") != std::string::npos) return true;
  const bool by_name = path.find("friction.") != std::string::npos ||
                       path.rfind("platforms", 0) == 0 || path.rfind("couplings", 0) == 0;
  const std::string leaf = path.substr(path.rfind('.') + 1);
  return by_name && text.find("`" + leaf + "`") != std::string::npos;
}

TEST(ContractDoc, NamesEveryKeyOfBothRigForms) {
  const std::string text = page();
  for (const Schema* s : {&rigfile::physicalSchema(), &rigfile::scaledSchema()}) {
    std::vector<std::string> paths;
    keyPaths(*s, "", paths);
    ASSERT_GT(paths.size(), 20u);
    for (const std::string& p : paths) {
      if (p.rfind("platforms.N.metronomes.N.", 0) == 0) continue;  // "the keys of section 1a"
      // written out, alone or as the start of a longer key (`platform.` of `platform.mass`)
      EXPECT_TRUE(named(text, p) || text.find("`" + p + ".") != std::string::npos)
          << "docs/contract.md does not name the key " << p;
    }
  }
}

TEST(ContractDoc, NamesEveryOutputFileOfEveryCommand) {
  const std::string text = page();
  std::set<std::string> files(OutputDir::outputNames().begin(), OutputDir::outputNames().end());
  // the files each command's --help names ("Files in --out DIR: ...")
  const testing_support::CommandResult top = testing_support::runMetrosync("--help");
  const std::regex command(R"(\n  ([a-z][a-z-]+) )"),
      file(R"((?:^|[^/\w.-])([a-z][a-z0-9_.-]*\.(csv|json|png|svg|pdf|yaml|md|gz|mp4|gif))\b)");
  int commands = 0;
  for (std::sregex_iterator c(top.out.begin(), top.out.end(), command), end; c != end; ++c) {
    ++commands;
    const std::string help = testing_support::runMetrosync((*c)[1].str() + " --help").out;
    for (std::sregex_iterator f(help.begin(), help.end(), file); f != end; ++f)
      files.insert((*f)[1].str());
  }
  EXPECT_GE(commands, 12);
  EXPECT_GE(files.size(), 30u);
  for (const std::string& f : files)
    EXPECT_NE(text.find(f), std::string::npos) << "docs/contract.md does not name " << f;
}

TEST(ContractDoc, NamesEveryRegimeLabelAndExitCode) {
  const std::string text = page();
  for (int r = 0; r <= static_cast<int>(Regime::Unknown); ++r) {
    const std::string name = toString(static_cast<Regime>(r));
    EXPECT_NE(text.find("`" + name + "`"), std::string::npos) << name;
  }
  for (const char* network :
       {"synchronized", "antiphase-groups", "chimera", "coherent-groups", "disordered"})
    EXPECT_NE(text.find(std::string("`") + network + "`"), std::string::npos) << network;
  for (int code : {cli::kSuccess, cli::kOtherError, cli::kBadInput, cli::kSimulationFailed})
    EXPECT_NE(text.find("| " + std::to_string(code) + " | "), std::string::npos) << code;
}

// The paper is cited by title, authors and journal, and nothing points outside the repository.
TEST(ContractDoc, CitesThePaperAndStaysInsideTheRepository) {
  const std::string text = page();
  for (const char* part :
       {"Coupled metronomes on a moving platform with Coulomb friction", "Goldsztein", "English",
        "Behta", "Finder", "Nadeau", "Strogatz", "Chaos **32**, 043119 (2022)"})
    EXPECT_NE(text.find(part), std::string::npos) << part;
  EXPECT_EQ(text.find("../shared"), std::string::npos);
  EXPECT_EQ(text.find("SPEC"), std::string::npos);
}

}  // namespace
}  // namespace metrosync
