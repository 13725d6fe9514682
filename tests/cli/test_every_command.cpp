// `metrosync CMD ...` builds only CMD's group of sub-commands (tools/cli/every_command.h): the
// groups together are the whole tree, each registers exactly the names it declares, and a command
// line run on its group alone prints, refuses and exits exactly as on the whole tree (help, parse
// errors, a missing rig file).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tools/cli/command_line.h"
#include "tools/cli/every_command.h"

namespace {

namespace cli = metrosync::cli;

std::vector<std::string> subcommandNames(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

TEST(EveryCommand, EachGroupRegistersExactlyItsNames) {
  for (size_t g = 0; g < cli::EveryCommand::groups().size(); ++g) {
    CLI::App app;
    cli::configureApp(app);
    cli::EveryCommand every;
    const auto commands = every.addGroup(app, g);
    EXPECT_EQ(subcommandNames(app), cli::EveryCommand::groups()[g]) << "group " << g;
    EXPECT_EQ(commands.size(), cli::EveryCommand::groups()[g].size()) << "group " << g;
  }
}

TEST(EveryCommand, TheGroupsInOrderAreTheWholeTree) {
  CLI::App app;
  cli::configureApp(app);
  cli::EveryCommand every;
  every.addAll(app);
  std::vector<std::string> declared;
  for (const auto& g : cli::EveryCommand::groups())
    declared.insert(declared.end(), g.begin(), g.end());
  EXPECT_EQ(subcommandNames(app), declared);
  std::vector<std::string> sorted = declared;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "a name twice";
}

struct Outcome {
  int code = -1;
  std::string out, err;
};

// The command line run as `metrosync` would, on the tree add() builds for it (lazy) or on every
// group (whole).
Outcome runOn(std::vector<std::string> words, bool whole) {
  words.insert(words.begin(), "metrosync");
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  const int argc = static_cast<int>(argv.size());
  CLI::App app;
  cli::configureApp(app);
  cli::EveryCommand every;
  const auto commands = whole ? every.addAll(app) : every.add(app, argc, argv.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  Outcome o;
  o.code = cli::runCommandLine(app, commands, argc, argv.data());
  o.out = testing::internal::GetCapturedStdout();
  o.err = testing::internal::GetCapturedStderr();
  return o;
}

TEST(EveryCommand, OneGroupAnswersAsTheWholeTree) {
  std::vector<std::vector<std::string>> lines;
  for (const auto& g : cli::EveryCommand::groups())
    for (const std::string& name : g) {
      lines.push_back({name, "--help"});
      lines.push_back({name, "--no-such-option"});
    }
  lines.push_back({"run", "compare"});  // a command's name where the rig goes: no such file
  lines.push_back({"run", "a.yaml", "b.yaml"});
  lines.push_back({"run", "--set"});
  lines.push_back({"scale", "--json", "--set", "x"});
  lines.push_back({"sweep"});
  lines.push_back({"fit"});
  lines.push_back({"merge"});
  lines.push_back({"continue", "--help-all"});
  for (const auto& words : lines) {
    std::string shown;
    for (const std::string& w : words) shown += w + " ";
    const Outcome lazy = runOn(words, false), whole = runOn(words, true);
    EXPECT_EQ(lazy.code, whole.code) << shown;
    EXPECT_EQ(lazy.out, whole.out) << shown;
    EXPECT_EQ(lazy.err, whole.err) << shown;
    if (words.size() == 2 && words[1] == "--help") {
      EXPECT_NE(lazy.out.find(words[0]), std::string::npos) << shown;
    }
  }
}

// Without a command, with --help or a misspelt command every group is built: the top-level help
// lists every command, and a misspelt one is matched against all of them.
TEST(EveryCommand, NoCommandBuildsEveryGroup) {
  const Outcome help = runOn({"--help"}, false);
  EXPECT_EQ(help.code, 0);
  for (const auto& g : cli::EveryCommand::groups())
    for (const std::string& name : g) EXPECT_NE(help.out.find(name), std::string::npos) << name;
  EXPECT_EQ(help.out, runOn({"--help"}, true).out);
  const Outcome typo = runOn({"sweeppoint"}, false);
  EXPECT_EQ(typo.code, 2);
  EXPECT_NE(typo.err.find("did you mean 'sweep-point'"), std::string::npos) << typo.err;
}

}  // namespace
