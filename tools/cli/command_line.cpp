#include "tools/cli/command_line.h"

#include <algorithm>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

#include "sim/engines/plugin_loader.h"
#include "sim/record/atomic_file.h"
#include "sim/record/safe_open.h"
#include "tools/cli/engines.h"
#include "tools/cli/number_option.h"
#include "tools/cli/range_warnings.h"
#include "tools/report/build_info.h"
#include "tools/report/plot.h"
#include "yaml/rig_loader.h"
#include "yaml/spelling.h"
#include "yaml/utf8.h"

namespace metrosync::cli {

namespace {

// RIG, --set, --out, --quiet: shared by run and compare (scale has no --out).
void addRigOptions(CLI::App* cmd, Options& opt, bool with_out) {
  cmd->add_option(
      "RIG", opt.rig_path,
      "rig file (YAML, docs/contract.md section 1); default: the built-in rig, the paper's "
      "experiment (two Wittner metronomes on low-friction rollers, started near "
      "antiphase)");
  cmd->add_option("--set", opt.sets,
                  "override a rig key, e.g. --set platform.friction.mu=0.3, "
                  "--set metronomes.1.start.phi=3.54 (list indices from 0); repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  addStrictFlag(cmd, opt.strict);
  if (with_out) {
    cmd->add_option("--out", opt.out,
                    "output directory (default: runs/<rig name>-<command>, with -<hash of the "
                    "--set overrides> appended when there are any); metrosync's own output "
                    "files already there are replaced")
        ->type_name("DIR");
    addNumber(cmd, "--max-output", opt.max_output, kPositive,
              "refuse a run that would write more than BYTES (estimated from the run's "
              "length and simulation.sample; docs/rig-limits.md)")
        ->type_name("BYTES")
        ->default_str("2e9");
    cmd->add_flag("-q,--quiet", opt.quiet,
                  "no summary on stdout (errors and warnings still go "
                  "to stderr)");
    cmd->add_option("--plot-format", opt.plot_format,
                    "format of the plots: png (default), svg or pdf (gnuplot's pngcairo, svg and "
                    "pdfcairo terminals)")
        ->check(CLI::IsMember(plotFormats()))
        ->capture_default_str();
    cmd->add_flag("--no-plot", opt.no_plot,
                  "write no plot (the CSV and JSON files only; saves the plotting child "
                  "process, most of a short run's time)");
  }
}

const char* kExitCodes =
    "Exit codes: 0 success; 2 bad command line or rig (nothing written); 3 the simulation failed "
    "(files written so far kept, summary.json says complete: false); 1 anything else.";

}  // namespace

void configureApp(CLI::App& app) {
  // the full model's engines from the registry, the default first (sim/engines/engine.h)
  std::string full;
  for (const Engine* e : engines())
    if (e->model() == "full")
      full += (full.empty() ? e->name() + " (the default)" : ", " + e->name());
  app.description(
      "metrosync: coupled metronomes on a platform with Coulomb (dry) friction. The full model: "
      "the governing equations with true stick-slip of the platform and each escapement tick "
      "an impulse, run by the engines " +
      full +
      " (choose with --engine); the slow flow: the "
      "two-timescale analysis's averaged equations. Runs, comparisons, sweeps, basins, "
      "continuation, fits, "
      "the paper's figures and animations, one subcommand each.");
  app.name("metrosync");
  app.set_version_flag("--version", versionText());
  app.require_subcommand(1);
  app.footer(kExitCodes);
}

namespace {

CLI::App* addRunCommand(CLI::App& app, Options& opt) {
  CLI::App* run = app.add_subcommand("run", "simulate a rig: envelope, regime, plots");
  addRigOptions(run, opt, true);
  run->add_option("--model", opt.model,
                  "full: the governing equations, integrated exactly (stick-slip and escapement "
                  "events); slow: the slow flow (default: the --engine's model, else full)")
      ->check(CLI::IsMember({"full", "slow"}));
  // the registry checks --engine (and its model) with the rig, so that the message can say why
  run->add_option("--engine", opt.engine, anyEngineHelp());
  run->footer(
      "Integrators of the full model (rig key simulation.integrator, e.g. --set "
      "simulation.integrator=verner76): " +
      integratorHelp() +
      ". Accuracy: simulation.accuracy (relative local error target, default 1e-8).\n"
      "Files in --out DIR: trajectory.csv and events.csv (full model), envelope.csv, "
      "envelope.png (.svg, .pdf with --plot-format), summary.json (with resolved_rig: the rig "
      "after --set, runnable as is; docs/outputs.md).\n" +
      kExitCodes);
  return run;
}

CLI::App* addCompareCommand(CLI::App& app, Options& opt) {
  CLI::App* compare = app.add_subcommand(
      "compare", "run the full model and the slow flow on one rig and compare their envelopes");
  addRigOptions(compare, opt, true);
  compare->add_option("--engine", opt.engine, fullEngineHelp());
  compare->footer(
      "Files in --out DIR: trajectory.csv, events.csv, envelope_full.csv, envelope_slow.csv, "
      "comparison.csv "
      "(tau, A_i full/slow, psi_j full/slow), comparison.png, summary.json (top-level keys: the "
      "full model; models.full, models.slow: each model; comparison: max |dA_i|, max |dpsi_j| "
      "modulo 2 pi).\n" +
      std::string(kExitCodes));
  return compare;
}

CLI::App* addScaleCommand(CLI::App& app, Options& opt) {
  CLI::App* scale = app.add_subcommand("scale", "print the scaled parameters of a rig");
  addRigOptions(scale, opt, false);
  scale->add_flag("--json", opt.json,
                  "exactly one JSON object: epsilon, mu (or c), nu, J, theta_c, alpha, zeta, "
                  "A_star, time_scale");
  scale->footer(kExitCodes);
  return scale;
}

// The handler's outcome as an exit code: every error printed as "metrosync: error: ...".
int exitCodeOf(const std::function<int()>& handler) {
  try {
    return handler();
  } catch (const RigError& e) {
    std::cerr << "metrosync: error: " << terminalText(e.what()) << "\n";
    return kBadInput;
  } catch (const UsageError& e) {
    std::cerr << "metrosync: error: " << terminalText(e.what()) << "\n";
    return kBadInput;
  } catch (const UnsafeFileError& e) {  // a link or FIFO planted in the output folder
    std::cerr << "metrosync: error: " << terminalText(e.what()) << "\n";
    return kBadInput;
  } catch (const PluginError& e) {  // a plugin missing from the installation
    std::cerr << "metrosync: error: " << terminalText(e.what()) << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "metrosync: error: " << terminalText(e.what()) << "\n";
    return kOtherError;
  } catch (...) {
    std::cerr << "metrosync: error: unexpected failure\n";
    return kOtherError;
  }
}

}  // namespace

std::vector<Command> addRigCommands(CLI::App& app, Options& opt) {
  return {{addRunCommand(app, opt), [&opt] { return runCommand(opt); }},
          {addCompareCommand(app, opt), [&opt] { return compareCommand(opt); }},
          {addScaleCommand(app, opt), [&opt] { return scaleCommand(opt); }}};
}

namespace {

// `metrosync runn`: the first word names no command; what it is closest to, else every command.
std::optional<std::string> unknownCommand(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return std::nullopt;
  const std::string word = argv[1];
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  if (std::find(names.begin(), names.end(), word) != names.end()) return std::nullopt;
  if (const auto c = rigfile::closest(word, names))
    return "unknown command '" + word + "' (did you mean '" + *c + "'?)";
  std::string all;
  for (const std::string& n : names) all += (all.empty() ? "" : ", ") + n;
  return "unknown command '" + word + "' (the commands: " + all + ")";
}

}  // namespace

int runCommandLine(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv) {
  setCommandLine(argc, argv);  // summary.json's command_line
  if (const auto unknown = unknownCommand(app, argc, argv)) {
    std::cerr << "metrosync: error: " << terminalText(*unknown) << "\n"
              << "Run 'metrosync --help' for usage.\n";
    return kBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0 through here; every parse error is a bad command line
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "metrosync: error: " << terminalText(e.what()) << "\n"
              << "Run 'metrosync --help' (or 'metrosync COMMAND --help') for usage.\n";
    return kBadInput;
  }
  for (const Command& c : commands)
    if (c.app->parsed()) return exitCodeOf(c.handler);
  return kBadInput;
}

}  // namespace metrosync::cli
