// metrosync's whole command line as tools/metrosync.cpp builds it, parsed without running any
// command: the `options` fuzz target (tools/fuzz/fuzz_entries.h) and the hostile tests' numeric
// fuzz pass (tests/hostile/test_number_options.cpp).
#pragma once

#include <string>
#include <vector>

#include "tools/cli/animate.h"
#include "tools/cli/basin.h"
#include "tools/cli/command_line.h"
#include "tools/cli/continue.h"
#include "tools/cli/figures.h"
#include "tools/cli/fit.h"
#include "tools/cli/sweep.h"
#include "tools/cli/sweep_point.h"
#include "tools/cli/validate.h"

namespace metrosync::fuzz {

struct CommandLineParser {
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
  cli::SweepCommands sweeps;
  CLI::App* basin_app = nullptr;

  CommandLineParser() {
    cli::configureApp(app);
    cli::addRigCommands(app, opt);
    sweeps = cli::addSweepCommands(app, sweep);
    cli::addValidateCommand(app, validate);
    cli::addContinueCommand(app);
    cli::addFitCommand(app, fit);
    cli::addMeasureCommand(app, measure);
    cli::addFiguresCommand(app, figures);
    cli::addAnimateCommand(app, animate);
    basin_app = cli::addBasinCommand(app, basin);
    cli::addSweepPointCommand(app, point);
  }
  CommandLineParser(const CommandLineParser&) = delete;
  CommandLineParser& operator=(const CommandLineParser&) = delete;

  // Every command's options at their defaults (the app, built once, keeps its bindings to them;
  // CLI11 clears an app's results before each parse).
  void reset() {
    opt = {}, sweep = {}, validate = {}, fit = {}, measure = {}, figures = {}, animate = {};
    basin = {}, point = {};
  }

  // `metrosync ARGS...` parsed: "" when it parses, else the parser's message (CLI11's or the
  // number rule's, tools/cli/number_option.h).
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

}  // namespace metrosync::fuzz
