#include "tools/cli/network_run.h"

#include <iostream>

#include "sim/engines/engine.h"
#include "tools/cli/engines.h"
#include "tools/report/network_files.h"
#include "tools/report/outputs.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

Network loadNetwork(const Options& opt) {
  LoadOptions lo;
  lo.max_output_bytes = opt.max_output;
  for (const Engine* e : engines())
    for (const std::string& n : e->integrators()) lo.integrators.push_back(n);
  lo.integrator_help = "one of: " + integratorHelp();
  return loadNetworkFile(opt.rig_path, opt.sets, lo);
}

// The engine that runs the network: the full model's, as for a single rig (--engine, else the
// one simulation.integrator names, else direct); the slow flow is refused.
const Engine& networkEngine(const Options& opt, const Network& net) {
  const std::string what = "a network of " + std::to_string(net.platforms.size()) + " platforms";
  if (opt.model == "slow")
    throw UsageError("--model slow: the slow flow is single-platform; " + what +
                     " runs the full model only (--engine direct or simbody)");
  const Engine& e = chooseEngine(opt.engine, "", net.platforms.at(0).rig, opt.rig_path);
  if (!e.runsNetworks())
    throw UsageError("--engine " + e.name() + ": " + what +
                     " runs the full model only (--engine direct or simbody)");
  return e;
}

OutputDir openDir(const Options& opt, const Network& net) {
  try {
    OutputDir dir(opt.out.empty() ? defaultOutputDir(net.name, "run", opt.sets) : opt.out);
    dir.removeStaleOutputs();
    return dir;
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
}

}  // namespace

bool isNetworkRun(const Options& opt) {
  if (opt.rig_path.empty()) return false;
  if (!isNetworkText(readRigFile(opt.rig_path))) return false;
  return !loadNetwork(opt).isSingleRig();
}

int runNetworkCommand(const Options& opt) {
  const Network net = loadNetwork(opt);
  const Engine& engine = networkEngine(opt, net);
  installStopHandlers();
  const OutputDir dir = openDir(opt, net);
  NetworkFiles files(dir, net);
  const NetworkRunReport report = engine.runNetwork(net, files);
  files.commit();
  nlohmann::json summary = files.summary(report);
  summary["model"] = "full";
  summary["rig"] = net.name;
  summary["units"] = "physical";
  std::vector<std::string> names = files.fileNames();
  for (const std::string& png : plotNetwork(
           dir, files, net, net.name + " - " + summary["network"]["regime"].get<std::string>()))
    names.push_back(png);
  names.push_back("summary.json");
  summary["files"] = names;
  addProvenance(summary,  // resolved_rig, command_line, build (docs/outputs.md)
                resolvedRigJson(opt.rig_path.empty() ? defaultRigYaml() : readRigFile(opt.rig_path),
                                opt.rig_path.empty() ? "<default rig>" : opt.rig_path, opt.sets));
  writeSummary(dir, summary);  // last: a summary.json means the run's files are all there
  if (!opt.quiet)
    std::cout << "network of " << net.platforms.size() << " platforms (" << engine.name() << ", "
              << report.integrator << "): " << summary["network"]["regime"].get<std::string>()
              << ", r = " << summary["network"]["r"].get<double>() << "\nfiles in " << dir.path()
              << "\n";
  if (!report.complete) {
    std::cerr << "metrosync: error: full model: " << report.failure << "\n";
    return kSimulationFailed;
  }
  return kSuccess;
}

}  // namespace metrosync::cli
