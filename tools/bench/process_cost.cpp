#include "tools/bench/process_cost.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tools/bench/subprocess.h"

namespace metrosync::bench {

namespace {

namespace fs = std::filesystem;

double wallSeconds(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  if (!in) throw std::invalid_argument("no summary.json");
  try {
    return nlohmann::json::parse(in).at("wall_seconds").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("summary.json: ") + e.what());
  }
}

// One run, or why it failed.
ProcessSample oneRun(const std::vector<std::string>& base, const fs::path& out) {
  std::vector<std::string> argv = base;
  argv.insert(argv.end(), {"--out", out.string()});
  const ProcessResult pr = runProcess(argv, 0.0, {"METROSYNC_PHASES=1"});
  if (!pr.ok())
    throw std::invalid_argument("exit " + std::to_string(pr.exit_code) + ": " +
                                (pr.err.empty() ? pr.error : pr.err.substr(0, pr.err.find('\n'))));
  ProcessSample s;
  s.start_s = pr.start_s;
  s.end_s = pr.end_s;
  s.cpu_s = pr.cpu_s;
  s.marks = parsePhases(pr.err);
  s.wall_seconds = wallSeconds(out);
  return s;
}

}  // namespace

ProcessMeasurement measureProcess(const ProcessOptions& o, const BenchOptions& c) {
  if (!fs::is_regular_file(o.scene)) throw std::invalid_argument(o.scene + ": no such rig file");
  const std::vector<std::string> base = {o.metrosync, "run", o.scene, "--quiet", "--no-plot"};
  ProcessMeasurement m;
  m.command = shellCommand(base);
  const fs::path out =
      fs::temp_directory_path() / ("metrosync-bench-process-" + std::to_string(::getpid()));
  std::vector<ProcessSample> runs;
  std::vector<double> loads;
  try {
    for (int k = 0; k <= o.repeat; ++k) {
      loads.push_back(waitForLoad(c));
      ProcessSample s = oneRun(base, out);
      fs::remove_all(out);
      if (k > 0) runs.push_back(std::move(s));  // the first warms the page cache
    }
    m.breakdown = processBreakdown(runs);
  } catch (const std::invalid_argument& e) {
    m.failure = e.what();
  }
  fs::remove_all(out);
  m.load_min = *std::min_element(loads.begin(), loads.end());
  m.load_max = *std::max_element(loads.begin(), loads.end());
  return m;
}

}  // namespace metrosync::bench
