// sweep's and merge's command lines (tools/cli/sweep.h).
#include "tools/cli/sweep_options.h"

#include "tools/cli/engines.h"
#include "tools/cli/number_option.h"
#include "tools/cli/range_warnings.h"
#include "tools/report/plot.h"

namespace metrosync::cli {

namespace {

// sweep's --force, --map, --basin-samples, --random and --seed.
void addSweepMapAndBasinOptions(CLI::App& sweep, SweepOptions& opt) {
  sweep.add_flag("--force", opt.force,
                 "run a grid of more than 10^7 points (without it such a grid is refused)");
  sweep
      .add_option("--map", opt.map,
                  "the two --vary keys the maps draw, across then up (default: the first two); "
                  "every combination of the other keys' values gets its own maps, "
                  "regimes--KEY=VALUE.png, ...")
      ->type_name("KEY1,KEY2");
  addInteger(&sweep, "--basin-samples", opt.basin_samples, 1, 1000000,
             "with --random: also run S random starts at every point and give the fraction "
             "that ends in-phase (column in_phase_fraction, map basin.png; docs/basin.md)")
      ->type_name("S");
  sweep
      .add_option("--random", opt.random,
                  "with --basin-samples: a start key drawn uniformly from FROM to TO (angles on "
                  "the circle), as for `metrosync basin`; repeatable")
      ->type_name("KEY=FROM:TO")
      ->allow_extra_args(false);
  addSeed(&sweep, "--seed", opt.seed, "with --basin-samples: the seed of the draws (default 1)");
}

}  // namespace

namespace {

// sweep's inputs and how it runs: RIG, --vary, --set, --model, --engine, --jobs, --resume,
// --shard, --out, -q.
void addSweepRunOptions(CLI::App& sweep, SweepOptions& opt) {
  sweep.add_option(
      "RIG", opt.rig_path,
      "rig file (YAML, docs/contract.md section 1); default: the built-in rig (the paper's "
      "experiment)");
  sweep
      .add_option(
          "--vary", opt.vary,
          "a key and its values: COUNT values from FROM to TO, both included; ':open' "
          "leaves TO out ([FROM, TO), for angles); ':log' spaces them evenly in log "
          "(0 < FROM <= TO); or the values listed, V1,V2,... or one value V "
          "(e.g. platform.friction.mu=0.2,0.3,0.4). Values may use pi: "
          "--vary platform.friction.mu=0:0.8:41, --vary "
          "metronomes.0.start.phi=0:2pi:100:open, --vary platform.friction.mu=0.01:10:31:log. "
          "metronomes.*.KEY sets KEY of every metronome (--vary metronomes.*.nu=0.5:0.8:4). "
          "Repeatable: one axis each, an N-D grid (the first the slowest; the maps draw "
          "two, see --map)")
      ->type_name("KEY=FROM:TO:COUNT[:open][:log]|V1,V2,..")
      ->required()
      ->allow_extra_args(false);
  sweep
      .add_option("--set", opt.sets,
                  "override a rig key for every point, e.g. --set simulation.tau=100; repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  sweep
      .add_option("--model", opt.model,
                  "slow: the slow flow; full: the full model (default: the --engine's model, "
                  "else slow; full for a network of platforms, docs/networks.md)")
      ->check(CLI::IsMember({"slow", "full"}));
  sweep.add_option("--engine", opt.engine, anyEngineHelp());
  addInteger(&sweep, "--jobs", opt.jobs, 1, kMaxJobs,
             "worker threads (default: the number of cores; never more than the points); the "
             "results do not depend on it");
  addStrictFlag(&sweep, opt.strict);
  sweep.add_flag("--resume", opt.resume,
                 "continue the sweep in --out DIR: points already in its regimes.csv are "
                 "kept, the others run (the command line must be the same)");
  sweep
      .add_option("--shard", opt.shard,
                  "run only the K-th of N slices of the grid (points with index mod N = "
                  "K-1); join the slices with `metrosync merge`")
      ->type_name("K/N");
  sweep
      .add_option("--out", opt.out,
                  "output directory (default: runs/<rig name>-sweep); metrosync's own output "
                  "files already there are replaced (unless --resume)")
      ->type_name("DIR");
  sweep.add_flag("-q,--quiet", opt.quiet,
                 "no progress bar and no summary (errors and warnings still go to stderr)");
}

// sweep's outputs: the maps' axes and basin samples, --boundaries, --no-plot, --plot-format,
// --keep, and the footer.
void addSweepOutputOptions(CLI::App& sweep, SweepOptions& opt) {
  addSweepMapAndBasinOptions(sweep, opt);
  sweep.add_flag("--boundaries", opt.boundaries,
                 "with --model slow over two ranges: the slow flow's fold and Hopf curves "
                 "(continuation) over the regime map, boundaries.csv");
  sweep.add_flag("--no-plot", opt.no_plot,
                 "draw no maps (regimes.csv, sweep.json and timings.csv only)");
  sweep
      .add_option("--plot-format", opt.plot_format,
                  "format of the maps: png (default), svg or pdf (gnuplot's pngcairo, svg and "
                  "pdfcairo terminals)")
      ->check(CLI::IsMember(plotFormats()))
      ->capture_default_str();
  sweep
      .add_option("--keep", opt.keep,
                  "envelope: keep every point's envelope rows in DIR/envelopes.csv.gz (one "
                  "gzip'd CSV with a point column; docs/sweep-points.md); `metrosync "
                  "sweep-point DIR INDEX` re-runs one point with full outputs")
      ->check(CLI::IsMember({"envelope"}));
  sweep.footer(
      "Files in --out DIR: regimes.csv (one row per grid point, appended as points finish, "
      "sorted by grid index at the end: the varied keys, regime, A_1..A_N, psi_2..psi_N (final, "
      "psi in [0, 2 pi)), r, s (= |Z|/mu: <= 1 a stuck platform), clusters, tau, complete, "
      "index, message), sweep.json (what was "
      "swept, how far it got), timings.csv (wall and CPU seconds per point, and the CPU seconds "
      "inside the engine), regimes.png, "
      "amplitudes.png, phases.png, order.png (N >= 3), drive.png (Coulomb platforms); with more "
      "than two --vary one set of maps per value of the keys not drawn (regimes--KEY=VALUE.png); "
      "with --basin-samples the column in_phase_fraction (after tau) and basin.png.\n"
      "A point whose run fails is recorded with regime 'failed' and the reason; the sweep goes "
      "on. A progress bar with ETA goes to stderr when it is a terminal; otherwise a line at every "
      "10% of a sweep that has run for 5 s. SIGINT/SIGTERM stop the "
      "sweep (the points in flight are not recorded; exit 3): --resume continues it, as it does "
      "after kill -9.\n"
      "Exit codes: 0 success; 2 bad command line or rig (nothing written); 3 interrupted; 1 "
      "anything else.");
}

CLI::App* addMergeCommand(CLI::App& app, SweepOptions& opt) {
  CLI::App* merge =
      app.add_subcommand("merge", "join the regimes.csv of sweep shards into one, with maps");
  merge->add_option("DIR", opt.dirs, "output directories of `sweep --shard K/N` runs")
      ->required()
      ->check(CLI::ExistingDirectory);
  merge->add_option("--out", opt.out, "output directory (default: runs/<rig name>-merge)")
      ->type_name("DIR");
  merge->add_flag("-q,--quiet", opt.quiet, "no summary on stdout");
  merge
      ->add_option("--plot-format", opt.plot_format,
                   "format of the maps: png (default), svg or pdf")
      ->check(CLI::IsMember(plotFormats()))
      ->capture_default_str();
  merge->add_option("--map", opt.map, "the two --vary keys the maps draw (as for sweep)")
      ->type_name("KEY1,KEY2");
  merge->footer(
      "The directories must hold the same sweep (rig, --set, model, grid: their sweep.json "
      "says); points missing from all of them are reported and left white in the maps.\n"
      "Exit codes: 0 success; 2 bad command line or directories that do not belong together "
      "(nothing written); 1 anything else.");
  return merge;
}

}  // namespace

SweepCommands addSweepCommands(CLI::App& app, SweepOptions& opt) {
  SweepCommands c;
  c.sweep = app.add_subcommand(
      "sweep", "a grid of runs over one or more rig keys, in parallel and resumable: a regime map");
  addSweepRunOptions(*c.sweep, opt);
  addSweepOutputOptions(*c.sweep, opt);
  c.merge = addMergeCommand(app, opt);
  return c;
}

}  // namespace metrosync::cli
