#include "tools/bench/run_cost.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "base/number_text.h"
#include "tools/bench/bench_metrics.h"
#include "tools/bench/subprocess.h"
#include "yaml/rig_loader.h"

namespace metrosync::bench {

namespace {

namespace fs = std::filesystem;

std::string firstLine(const std::string& s) {
  return s.substr(0, s.find('\n'));
}

// A variant's items: KEY=VALUE overrides (--set), and env:NAME=VALUE the run's environment.
constexpr const char* kEnvItem = "env:";

std::vector<std::string> variantItems(const std::string& variant, bool env) {
  std::vector<std::string> v;
  std::stringstream ss(variant);
  for (std::string item; std::getline(ss, item, ' ');) {
    const bool is_env = item.rfind(kEnvItem, 0) == 0;
    if (!item.empty() && is_env == env) v.push_back(is_env ? item.substr(4) : item);
  }
  return v;
}
std::vector<std::string> splitSets(const std::string& variant) {
  return variantItems(variant, false);
}
std::vector<std::string> splitEnv(const std::string& variant) {
  return variantItems(variant, true);
}

std::vector<std::string> runArgs(const RunCostOptions& o, const std::string& scene,
                                 const std::string& variant) {
  std::vector<std::string> argv = {o.metrosync, "run"};
  if (scene != kDefaultRig) argv.push_back(scene);
  argv.insert(argv.end(), {"--quiet", "--no-plot"});
  for (const std::string& s : splitSets(variant)) argv.insert(argv.end(), {"--set", s});
  return argv;
}

// What one run's summary.json says.
struct Summary {
  double wall = 0.0, engine = 0.0;
  Method method;  // the engine, integrator and accuracy it ran
};

// A run's summary.json; false when unreadable.
bool readSummary(const fs::path& dir, Summary& s) {
  std::ifstream in(dir / "summary.json");
  if (!in) return false;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    s.wall = j.at("wall_seconds").get<double>();
    s.engine = j.at("engine_seconds").get<double>();
    s.method.engine = j.at("engine").get<std::string>();
    s.method.integrator = j.at("integrator").get<std::string>();
    s.method.accuracy = j.at("accuracy").get<double>();
    return true;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

// The same engine, integrator and accuracy on the same rig in this process, recording off:
// `repeat` runs, their wall median (NaN when a run fails).
double engineAlone(const RunCostOptions& o, const BenchOptions& c, const std::string& scene,
                   const std::string& variant, const Method& m) {
  const std::vector<std::string> sets = splitSets(variant);
  const Scene sc =
      scene == kDefaultRig ? sceneFromRig(kDefaultRig, defaultRig(sets)) : loadScene(scene, sets);
  std::vector<double> walls;
  for (int k = 0; k < o.repeat; ++k) {
    waitForLoad(c);
    const RunResult r = runOnce(sc, m, c.budget_s, Sampling::FinalState);
    if (!r.complete) return std::nan("");
    walls.push_back(r.wall_s);
  }
  return median(walls);
}

std::string field(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// One scene and variant: a warm-up run, then `repeat` counted ones.
RunCostRow measureOne(const RunCostOptions& o, const BenchOptions& c, const std::string& scene,
                      const std::string& variant, const fs::path& tmp) {
  RunCostRow row;
  row.scene = scene;
  row.variant = variant;
  const std::vector<std::string> base = runArgs(o, scene, variant);
  const std::vector<std::string> env = splitEnv(variant);
  row.command = shellCommand(env) + (env.empty() ? "" : " ") + shellCommand(base);
  std::vector<double> walls, engines, ratios, pwall, pcpu, loads;
  Summary sum;
  for (int k = 0; k <= o.repeat; ++k) {
    loads.push_back(waitForLoad(c));
    const fs::path out = tmp / ("r" + std::to_string(k));
    std::vector<std::string> argv = base;
    argv.insert(argv.end(), {"--out", out.string()});
    const ProcessResult pr = runProcess(argv, 0.0, env);
    const bool read = pr.ok() && readSummary(out, sum);
    const double wall = sum.wall, engine = sum.engine;
    fs::remove_all(out);
    if (!read) {
      row.failure = pr.ok() ? "no wall_seconds / engine_seconds in summary.json"
                            : "exit " + std::to_string(pr.exit_code) + ": " +
                                  firstLine(pr.err.empty() ? pr.error : pr.err);
      break;
    }
    if (k == 0) continue;  // the page cache's warm-up
    walls.push_back(wall), pwall.push_back(pr.wall_s), pcpu.push_back(pr.cpu_s);
    if (!(engine > 0 && engine <= wall)) {
      ++row.inconsistent;
      continue;
    }
    engines.push_back(engine), ratios.push_back(wall / engine);
  }
  row.runs = static_cast<int>(walls.size());
  row.wall_seconds = median(walls);
  row.engine_seconds = median(engines);
  row.ratio = median(ratios);
  row.ratio_min = ratios.empty() ? NAN : *std::min_element(ratios.begin(), ratios.end());
  row.ratio_max = ratios.empty() ? NAN : *std::max_element(ratios.begin(), ratios.end());
  if (row.failure.empty()) {
    row.engine = sum.method.engine + ":" + sum.method.integrator + ":" + sum.method.setting();
    row.engine_alone_s = engineAlone(o, c, scene, variant, sum.method);
    row.over_alone = row.wall_seconds / row.engine_alone_s;
  }
  row.process_wall_s = median(pwall);
  row.process_cpu_s = median(pcpu);
  row.load_min = *std::min_element(loads.begin(), loads.end());
  row.load_max = *std::max_element(loads.begin(), loads.end());
  return row;
}

}  // namespace

std::vector<RunCostRow> measureRunCost(const RunCostOptions& o, const BenchOptions& c) {
  for (const std::string& scene : o.scenes)
    if (scene != kDefaultRig && !fs::is_regular_file(scene))
      throw std::invalid_argument(scene + ": no such rig file");
  const fs::path tmp = fs::path(o.tmp.empty() ? fs::temp_directory_path().string() : o.tmp) /
                       ("metrosync-runcost-" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  std::vector<RunCostRow> rows;
  for (const std::string& scene : o.scenes) {
    for (const std::string& variant : o.variants) {
      rows.push_back(measureOne(o, c, scene, variant, tmp));
      const RunCostRow& r = rows.back();
      if (!c.quiet)
        std::cerr << "  run " << r.scene << (variant.empty() ? "" : " --set " + variant) << ": "
                  << (r.failure.empty()
                          ? "wall_seconds " + benchNumber(r.wall_seconds, 3) +
                                " s, engine_seconds " + benchNumber(r.engine_seconds, 3) +
                                " s, ratio " + benchNumber(r.ratio, 3, Notation::Fixed) +
                                ", engine alone " + benchNumber(r.engine_alone_s, 3) +
                                " s, wall / alone " + benchNumber(r.over_alone, 3, Notation::Fixed)
                          : "failed: " + r.failure)
                  << "\n";
    }
  }
  fs::remove_all(tmp);
  return rows;
}

std::string runCostCsv(const std::vector<RunCostRow>& rows) {
  std::string s =
      "scene,variant,runs,wall_seconds,engine_seconds,ratio,process_wall_s,process_cpu_s,"
      "load1_min,load1_max,target,inconsistent_splits,ratio_min,ratio_max,engine,engine_alone_s,"
      "wall_over_alone,failure\n";
  for (const RunCostRow& r : rows)
    s += field(r.scene) + "," + field(r.variant) + "," + std::to_string(r.runs) + "," +
         benchNumber(r.wall_seconds, 6) + "," + benchNumber(r.engine_seconds, 6) + "," +
         benchNumber(r.ratio, 6) + "," + benchNumber(r.process_wall_s, 6) + "," +
         benchNumber(r.process_cpu_s, 6) + "," + benchNumber(r.load_min, 2, Notation::Fixed) + "," +
         benchNumber(r.load_max, 2, Notation::Fixed) + "," +
         benchNumber(kRunRatioTarget, 2, Notation::Fixed) + "," + std::to_string(r.inconsistent) +
         "," + benchNumber(r.ratio_min, 6) + "," + benchNumber(r.ratio_max, 6) + "," +
         field(r.engine) + "," + benchNumber(r.engine_alone_s, 6) + "," +
         benchNumber(r.over_alone, 6) + "," + field(r.failure) + "\n";
  return s;
}

namespace {

// "1.23" against kRunRatioTarget, bold above it
std::string againstTarget(double ratio) {
  const std::string t = benchNumber(ratio, 2, Notation::Fixed);
  return !std::isfinite(ratio) || ratio <= kRunRatioTarget ? t : "**" + t + "**";
}

void runCostRow(std::ostringstream& os, const RunCostRow& r) {
  os << "| " << r.scene << " | " << (r.variant.empty() ? "-" : r.variant) << " | ";
  if (!r.failure.empty()) {
    os << "failed: " << r.failure << " |  |  |  |  |  |  |  |  |  |  |\n";
    return;
  }
  os << r.runs << " | " << benchNumber(1e3 * r.wall_seconds, 3) << " ms | "
     << benchNumber(1e3 * r.engine_seconds, 3) << " ms | " << againstTarget(r.ratio) << " ("
     << benchNumber(r.ratio_min, 2, Notation::Fixed) << "-"
     << benchNumber(r.ratio_max, 2, Notation::Fixed) << ") | "
     << benchNumber(1e3 * r.engine_alone_s, 3) << " ms | " << againstTarget(r.over_alone) << " | "
     << r.engine << " | " << benchNumber(1e3 * r.process_wall_s, 3) << " ms | "
     << benchNumber(1e3 * r.process_cpu_s, 3) << " ms | "
     << benchNumber(r.load_min, 2, Notation::Fixed) << "-"
     << benchNumber(r.load_max, 2, Notation::Fixed) << " | "
     << (r.inconsistent ? "**" + std::to_string(r.inconsistent) + "**" : "0") << " |\n";
}

}  // namespace

std::string runCostMarkdown(const std::vector<RunCostRow>& rows, const std::string& command) {
  std::ostringstream os;
  int met = 0, alone_met = 0, measured = 0;
  for (const RunCostRow& r : rows)
    if (r.failure.empty())
      ++measured, met += r.ratio <= kRunRatioTarget, alone_met += r.over_alone <= kRunRatioTarget;
  os << "`metrosync run SCENE --quiet --no-plot` (the built binary, files written; `default`: "
     << "the built-in default rig, no rig file): medians of summary.json's `wall_seconds` (the "
     << "integration with its recording) and `engine_seconds` (the integrator and its events), "
     << "the median of their ratio in each run (its range over the runs in parentheses), the "
     << "same engine, integrator and accuracy run in the bench's process with recording off "
     << "(engine alone, wall median) and `wall_seconds` over it (target <= "
     << benchNumber(kRunRatioTarget, 2, Notation::Fixed) << " for both ratios), and the whole "
     << "process measured from outside (start-up, rig, integration, files, exit; wall and CPU). "
     << "The first run of each row warms the page cache and is not counted. A run whose "
     << "engine_seconds is <= 0 or above its wall_seconds (an impossible split) is counted in "
     << "the last column and left out of the engine_seconds and ratio medians.\n\n"
     << "**`run` against the engine: wall_seconds / engine_seconds " << rowsVerdict(met, measured)
     << "; wall_seconds / engine alone " << rowsVerdict(alone_met, measured) << ".**\n\n"
     << "| scene | variant (--set, env:) | runs | wall_seconds | engine_seconds | wall / engine "
        "(range) | "
        "engine alone | wall / engine alone | engine | process wall | process CPU | load | "
        "impossible splits |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const RunCostRow& r : rows) runCostRow(os, r);
  if (!command.empty()) os << "\nMade by:\n\n    " << command << "\n";
  return os.str();
}

}  // namespace metrosync::bench
