#include "tools/cli/sweep_point.h"

#include <filesystem>
#include <limits>

#include "sim/analysis/sweep.h"
#include "sim/record/atomic_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/number_option.h"
#include "tools/report/sweep_files.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

CLI::App* addSweepPointCommand(CLI::App& app, SweepPointOptions& opt) {
  CLI::App* c = app.add_subcommand("sweep-point",
                                   "re-run one grid point of a sweep with full outputs and plots");
  c->add_option("DIR", opt.dir, "the sweep's output directory (with its sweep.json)")->required();
  addInteger(c, "INDEX", opt.index, 0, std::numeric_limits<long>::max(),
             "the grid index (regimes.csv's `index` column)")
      ->required();
  c->add_option("--out", opt.out, "output directory (default: DIR/point-INDEX)")->type_name("DIR");
  c->add_flag("-q,--quiet", opt.quiet, "no summary on stdout");
  c->add_flag("--no-plot", opt.no_plot, "write no plot");
  c->footer(
      "The point's rig: the rig text recorded in DIR/sweep.json (written to OUT/sweep-rig.yaml), "
      "the sweep's --set, then the point's --vary values; the sweep's model and engine. Files in "
      "OUT: those of `metrosync run` and sweep-rig.yaml.\n"
      "Exit codes: 0 success; 2 no sweep in DIR, or INDEX outside its grid; 3 the simulation "
      "failed; 1 anything else.");
  return c;
}

int sweepPointCommand(const SweepPointOptions& opt) {
  SweepManifest m;
  try {
    m = readSweepManifest(opt.dir);
  } catch (const SweepInputError& e) {
    throw UsageError(e.what());
  }
  if (opt.index < 0 || opt.index >= m.grid.size())
    throw UsageError("INDEX " + std::to_string(opt.index) + ": the grid of " + opt.dir +
                     " has the points 0.." + std::to_string(m.grid.size() - 1));
  Options run;
  run.out = opt.out.empty() ? opt.dir + "/point-" + std::to_string(opt.index) : opt.out;
  run.sets = m.sets;
  for (const auto& o : m.grid.overrides(opt.index)) run.sets.push_back(o);
  run.model = m.model;
  run.engine = m.engine;
  run.quiet = opt.quiet;
  run.no_plot = opt.no_plot;
  // the swept rig text, as recorded (the rig file may have changed since), checked with the
  // point's overrides before anything is written (a bad rig: exit 2, no point-N/)
  const std::string recorded = opt.dir + "/sweep.json (its rig_text)";
  if (isNetworkText(m.rig_text))
    loadNetworkText(m.rig_text, recorded, run.sets);
  else
    loadRigText(m.rig_text, recorded, run.sets);
  const bool made = !std::filesystem::exists(run.out);
  std::error_code ec;
  std::filesystem::create_directories(run.out, ec);
  if (ec) throw UsageError("--out " + run.out + ": " + ec.message());
  try {
    run.rig_path = run.out + "/sweep-rig.yaml";
    writeFileAtomically(run.rig_path, m.rig_text);
    if (!opt.quiet) {
      std::string values;
      for (const auto& o : m.grid.overrides(opt.index)) values += (values.empty() ? "" : ", ") + o;
      std::cout << "grid point " << opt.index << " of " << opt.dir << ": " << values << "\n";
    }
    return runCommand(run);
  } catch (const RigError&) {  // refused after all (an engine the point cannot use): undo
    if (made) std::filesystem::remove_all(run.out, ec);
    throw;
  } catch (const UsageError&) {
    if (made) std::filesystem::remove_all(run.out, ec);
    throw;
  }
}

}  // namespace metrosync::cli
