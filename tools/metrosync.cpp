// metrosync: the command line (SPEC section 2). Parses with CLI11 and maps every outcome to the
// SPEC section 5 exit codes: 0 success, 2 bad command line or rig (nothing written), 3 the
// simulation failed (files kept, marked incomplete), 1 anything else.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "tools/cli/commands.h"
#include "tools/cli/continue.h"
#include "tools/cli/engines.h"
#include "tools/cli/sweep.h"
#include "tools/cli/validate.h"
#include "tools/report/outputs.h"
#include "yaml/rig_loader.h"

namespace {

using metrosync::cli::Options;

// RIG, --set, --out, --quiet: shared by run and compare (scale has no --out).
void addRigOptions(CLI::App* cmd, Options& opt, bool with_out) {
  cmd->add_option("RIG", opt.rig_path,
                  "rig file (YAML, SPEC section 1); default: the built-in rig, the paper's "
                  "experiment (two Wittner metronomes on low-friction rollers, started near "
                  "antiphase)");
  cmd->add_option("--set", opt.sets,
                  "override a rig key, e.g. --set platform.friction.mu=0.3, "
                  "--set metronomes.1.start.phi=3.54 (list indices from 0); repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  if (with_out) {
    cmd->add_option("--out", opt.out,
                    "output directory (default: runs/<rig name>-<command>); metrosync's own "
                    "output files already there are replaced")
        ->type_name("DIR");
    cmd->add_option("--max-output", opt.max_output,
                    "refuse a run that would write more than BYTES (estimated from the run's "
                    "length and simulation.sample; docs/rig-limits.md)")
        ->type_name("BYTES")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    cmd->add_flag("-q,--quiet", opt.quiet,
                  "no summary on stdout (errors and warnings still go "
                  "to stderr)");
    cmd->add_flag("--no-plot", opt.no_plot,
                  "write no plot (the CSV and JSON files only; saves the plotting child "
                  "process, most of a short run's time)");
  }
}

const char* kExitCodes =
    "Exit codes: 0 success; 2 bad command line or rig (nothing written); 3 the simulation failed "
    "(files written so far kept, summary.json says complete: false); 1 anything else.";

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  CLI::App app{
      "metrosync: coupled metronomes on a platform with Coulomb (dry) friction - the full "
      "model (a Simbody multibody system with stick-slip and escapement events) and the "
      "slow flow of the two-timescale analysis."};
  app.name("metrosync");
  app.set_version_flag("--version", metrosync::metrosyncVersion());
  app.require_subcommand(1);
  app.footer(kExitCodes);

  CLI::App* run = app.add_subcommand("run", "simulate a rig: envelope, regime, plots");
  addRigOptions(run, opt, true);
  run->add_option("--model", opt.model,
                  "full: the governing equations, integrated exactly (stick-slip and escapement "
                  "events); slow: the slow flow (default: the --engine's model, else full)")
      ->check(CLI::IsMember({"full", "slow"}));
  // the registry checks --engine (and its model) with the rig, so that the message can say why
  run->add_option("--engine", opt.engine, metrosync::cli::anyEngineHelp());
  run->footer(
      "Integrators of the full model (rig key simulation.integrator, e.g. --set "
      "simulation.integrator=verner76): " +
      metrosync::integratorHelp() +
      ". Accuracy: simulation.accuracy (relative local error target, default 1e-8).\n"
      "Files in --out DIR: trajectory.csv (full model), envelope.csv, envelope.png, "
      "summary.json.\n" +
      kExitCodes);

  CLI::App* compare = app.add_subcommand(
      "compare", "run the full model and the slow flow on one rig and compare their envelopes");
  addRigOptions(compare, opt, true);
  compare->add_option("--engine", opt.engine, metrosync::cli::fullEngineHelp());
  compare->footer(
      "Files in --out DIR: trajectory.csv, envelope_full.csv, envelope_slow.csv, comparison.csv "
      "(tau, A_i full/slow, psi_j full/slow), comparison.png, summary.json (top-level keys: the "
      "full model; models.full, models.slow: each model; comparison: max |dA_i|, max |dpsi_j| "
      "modulo 2 pi).\n" +
      std::string(kExitCodes));

  CLI::App* scale = app.add_subcommand("scale", "print the scaled parameters of a rig");
  addRigOptions(scale, opt, false);
  scale->add_flag("--json", opt.json,
                  "exactly one JSON object: epsilon, mu (or c), nu, J, theta_c, alpha, zeta, "
                  "A_star, time_scale");
  scale->footer(kExitCodes);

  metrosync::cli::SweepOptions sweep_opt;  // sweep and merge (tools/cli/sweep.h)
  const metrosync::cli::SweepCommands sweep = metrosync::cli::addSweepCommands(app, sweep_opt);
  metrosync::cli::ValidateOptions validate_opt;  // tools/cli/validate.h
  CLI::App* validate = metrosync::cli::addValidateCommand(app, validate_opt);
  CLI::App* continue_cmd = metrosync::cli::addContinueCommand(app);  // tools/cli/continue.h

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0 through here; every parse error is a bad command line
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "metrosync: error: " << e.what() << "\n"
              << "Run 'metrosync --help' (or 'metrosync COMMAND --help') for usage.\n";
    return metrosync::cli::kBadInput;
  }

  try {
    if (run->parsed()) return metrosync::cli::runCommand(opt);
    if (compare->parsed()) return metrosync::cli::compareCommand(opt);
    if (scale->parsed()) return metrosync::cli::scaleCommand(opt);
    if (sweep.sweep->parsed()) return metrosync::cli::sweepCommand(sweep_opt);
    if (sweep.merge->parsed()) return metrosync::cli::mergeCommand(sweep_opt);
    if (validate->parsed()) return metrosync::cli::validateCommand(validate_opt);
    if (continue_cmd->parsed()) return metrosync::cli::continueCommand();
    return metrosync::cli::kBadInput;
  } catch (const metrosync::RigError& e) {
    std::cerr << "metrosync: error: " << e.what() << "\n";
    return metrosync::cli::kBadInput;
  } catch (const metrosync::cli::UsageError& e) {
    std::cerr << "metrosync: error: " << e.what() << "\n";
    return metrosync::cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "metrosync: error: " << e.what() << "\n";
    return metrosync::cli::kOtherError;
  } catch (...) {
    std::cerr << "metrosync: error: unexpected failure\n";
    return metrosync::cli::kOtherError;
  }
}
