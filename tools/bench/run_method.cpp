#include "tools/bench/run_method.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "base/number_text.h"
#include "sim/engines/direct/direct_integrators.h"
#include "tools/bench/bench_metrics.h"
#include "tools/bench/scaled_state.h"
#include "tools/bench/subprocess.h"

namespace metrosync::bench {

namespace {

namespace fs = std::filesystem;

std::string& givenPath() {
  static std::string p;
  return p;
}

// What one run left: its summary's timings and counts, its final state.
struct OneRun {
  double wall = 0.0, engine = 0.0;
  RunCounts counts;
  std::vector<double> final_row;  // trajectory.csv's last row, rig units
};

std::string firstLine(const std::string& s) {
  return s.substr(0, s.find('\n'));
}

// summary.json's timings and counts; throws std::invalid_argument saying what is missing.
OneRun readRun(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  if (!in) throw std::invalid_argument("no summary.json in " + dir.string());
  OneRun r;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (!j.at("complete").get<bool>())
      throw std::invalid_argument("incomplete: " + j.value("failure", std::string("?")));
    r.wall = j.at("wall_seconds").get<double>();
    r.engine = j.at("engine_seconds").get<double>();
    const nlohmann::json& c = j.at("counts");
    r.counts.steps = c.at("steps").get<long>();
    r.counts.rhs_evals = c.at("rhs_evals").get<long>();
    r.counts.events = c.at("events").get<long>();
    r.counts.stick_slip = c.at("stick_slip").get<long>();
    r.counts.escapements = c.at("escapements").get<std::vector<long>>();
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument("summary.json: " + std::string(e.what()));
  }
  r.final_row = lastCsvRow((dir / "trajectory.csv").string());
  if (r.final_row.empty()) throw std::invalid_argument("no final row in trajectory.csv");
  return r;
}

std::vector<std::string> runArgv(const Scene& scene, const Method& m, const fs::path& out) {
  std::vector<std::string> argv = {metrosyncPath(), "run", scene.path, "--quiet", "--no-plot"};
  if (m.accuracy > 0)
    argv.insert(argv.end(), {"--set", "simulation.accuracy=" + numberText(m.accuracy, 17)});
  if (!m.integrator.empty())
    argv.insert(argv.end(), {"--set", "simulation.integrator=" + m.integrator});
  argv.insert(argv.end(), {"--out", out.string()});
  return argv;
}

// The medians of the runs, the counts and final state of the first.
RunResult resultOf(const Scene& scene, const Method& m, const std::vector<OneRun>& runs) {
  RunResult r;
  r.method = m;
  std::vector<double> walls, engines, ratios;
  for (const OneRun& o : runs) {
    walls.push_back(o.wall);
    engines.push_back(o.engine);
    if (o.engine > 0) ratios.push_back(o.wall / o.engine);
  }
  r.wall_s = median(walls);
  r.cpu_s = std::nan("");
  r.engine_s = median(engines);
  r.wall_over_engine = median(ratios);
  r.counts = runs.front().counts;
  for (long e : r.counts.escapements) r.ticks += e;
  r.final_state = scaledFinalState(scene, runs.front().final_row);
  r.regime = "n/a (final state only)";
  return r;
}

}  // namespace

void setMetrosyncPath(const std::string& path) {
  givenPath() = path;
}

const std::string& metrosyncPath() {
  if (givenPath().empty()) {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    givenPath() = ec ? std::string("metrosync") : (self.parent_path() / "metrosync").string();
  }
  return givenPath();
}

std::string runMethodMissing() {
  if (::access(metrosyncPath().c_str(), X_OK) == 0) return "";
  return "the run method needs the metrosync binary: " + metrosyncPath() +
         " is not an executable file (--metrosync PATH)";
}

std::vector<std::string> runIntegratorNames() {
  return directIntegratorNames();
}

std::vector<double> lastCsvRow(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const std::streamoff size = in.tellg();
  const std::streamoff from = std::max<std::streamoff>(0, size - 65536);  // rows are far shorter
  std::string tail(static_cast<size_t>(size - from), '\0');
  in.seekg(from);
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
  const size_t start = tail.rfind('\n');
  if (start == std::string::npos && from > 0) return {};
  const std::string line = tail.substr(start == std::string::npos ? 0 : start + 1);
  std::vector<double> row;
  size_t at = 0;
  while (at <= line.size()) {
    const size_t comma = std::min(line.find(',', at), line.size());
    size_t used = 0;
    try {
      row.push_back(std::stod(line.substr(at, comma - at), &used));
    } catch (const std::exception&) {
      return {};
    }
    if (used != comma - at) return {};
    at = comma + 1;
  }
  return row;
}

RunCall runMetrosyncCommand(const Scene& scene, const Method& method, int repeat,
                            double timeout_s) {
  RunCall call;
  if (const std::string why = runMethodMissing(); !why.empty()) {
    call.result = failedRun(method, why);
    return call;
  }
  if (scene.path.empty()) {
    call.result = failedRun(
        method, "the run method needs a rig file (the scene " + scene.name + " was built in code)");
    return call;
  }
  const fs::path tmp = fs::temp_directory_path() /
                       ("metrosync-bench-run-" + std::to_string(::getpid()) + "-" + scene.name);
  std::vector<OneRun> runs;
  for (int k = 0; k < std::max(1, repeat); ++k) {
    const std::vector<std::string> argv = runArgv(scene, method, tmp);
    if (k == 0) call.command = shellCommand(argv);
    const ProcessResult pr = runProcess(argv, timeout_s);
    std::string why;
    if (!pr.ok()) {
      why = pr.timed_out ? "stopped after " + numberText(timeout_s, 3) + " s"
                         : "exit " + std::to_string(pr.exit_code) + ": " +
                               firstLine(pr.err.empty() ? pr.error : pr.err);
    } else {
      try {
        runs.push_back(readRun(tmp));
      } catch (const std::invalid_argument& e) {
        why = e.what();
      }
    }
    fs::remove_all(tmp);
    if (!why.empty()) {
      call.result = failedRun(method, "metrosync run failed (" + why + ")");
      call.result.over_budget = pr.timed_out;
      return call;
    }
  }
  call.result = resultOf(scene, method, runs);
  call.runs = static_cast<int>(runs.size());
  return call;
}

}  // namespace metrosync::bench
