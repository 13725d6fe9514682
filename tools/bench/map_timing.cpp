#include "tools/bench/map_timing.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "base/number_text.h"
#include "tools/bench/bench_metrics.h"
#include "tools/bench/subprocess.h"

namespace metrosync::bench {

namespace {

namespace fs = std::filesystem;

int sideOf(const std::string& map) {
  return map == "full" ? 64 : 100;
}

}  // namespace

std::vector<std::string> mapSweepArgs(const MapOptions& o, const std::string& map) {
  if (map != "full" && map != "slow")
    throw std::invalid_argument("map '" + map + "': full or slow");
  const std::string n = std::to_string(sideOf(map));
  return {o.metrosync,
          "sweep",
          o.rig,
          "--model",
          map,
          "--vary",
          "platform.friction.mu=0:0.8:" + n,
          "--vary",
          "metronomes.0.start.phi=0:6.283185307179586:" + n + ":open",
          "--jobs",
          std::to_string(o.jobs),
          "--no-plot",
          "-q"};
}

std::vector<MapRow> timeMaps(const MapOptions& o, const BenchOptions& c) {
  const fs::path tmp = fs::path(o.tmp.empty() ? fs::temp_directory_path().string() : o.tmp) /
                       ("metrosync-maps-" + std::to_string(::getpid()));
  std::vector<MapRow> rows;
  for (const std::string& map : o.maps) {
    MapRow row;
    row.map = map;
    row.points = sideOf(map) * sideOf(map);
    row.target_s = map == "full" ? kFullMapTargetS : kSlowMapTargetS;
    const std::vector<std::string> base = mapSweepArgs(o, map);
    row.command = shellCommand(base);
    std::vector<double> cpus, loads;
    for (int k = 0; k < o.repeat; ++k) {
      loads.push_back(waitForLoad(c));
      std::vector<std::string> argv = base;
      argv.insert(argv.end(), {"--out", (tmp / map).string()});
      const ProcessResult pr = runProcess(argv);
      fs::remove_all(tmp / map);
      if (!pr.ok()) {
        const std::string why = pr.err.empty() ? pr.error : pr.err;
        row.failure = "exit " + std::to_string(pr.exit_code) + ": " + why.substr(0, why.find('\n'));
        break;
      }
      row.walls.push_back(pr.wall_s);
      cpus.push_back(pr.cpu_s);
      if (!c.quiet)
        std::cerr << "  map " << map << ": " << benchNumber(pr.wall_s, 3) << " s wall, "
                  << benchNumber(pr.cpu_s, 3) << " s CPU, load "
                  << benchNumber(loads.back(), 2, Notation::Fixed) << "\n";
    }
    row.runs = static_cast<int>(row.walls.size());
    row.wall_s = median(row.walls);
    row.cpu_s = median(cpus);
    row.load_min = *std::min_element(loads.begin(), loads.end());
    row.load_max = *std::max_element(loads.begin(), loads.end());
    rows.push_back(row);
  }
  fs::remove_all(tmp);
  return rows;
}

std::string mapsCsv(const std::vector<MapRow>& rows) {
  std::string s = "map,points,runs,wall_s,cpu_s,target_s,load1_min,load1_max,failure\n";
  for (const MapRow& r : rows) {
    std::string failure = r.failure;
    std::replace(failure.begin(), failure.end(), ',', ';');
    s += r.map + "," + std::to_string(r.points) + "," + std::to_string(r.runs) + "," +
         benchNumber(r.wall_s, 6) + "," + benchNumber(r.cpu_s, 6) + "," +
         benchNumber(r.target_s, 6) + "," + benchNumber(r.load_min, 2, Notation::Fixed) + "," +
         benchNumber(r.load_max, 2, Notation::Fixed) + "," + failure + "\n";
  }
  return s;
}

std::string mapsMarkdown(const std::vector<MapRow>& rows) {
  std::ostringstream os;
  os << "`metrosync sweep` of the experiment map (mu = 0 .. 0.8 x phi0 = 0 .. 2 pi open, "
        "tau 305.6, --jobs 2, no maps drawn), wall time from outside (median) and the process's "
        "CPU time (all threads):\n\n"
        "| map | points | runs | wall | target | CPU | load | wall of each run |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const MapRow& r : rows) {
    os << "| " << r.map << " " << sideOf(r.map) << " x " << sideOf(r.map) << " | " << r.points
       << " | ";
    if (!r.failure.empty()) {
      os << "failed: " << r.failure << " |  |  |  |  |  |\n";
      continue;
    }
    std::string each;
    for (double w : r.walls) each += (each.empty() ? "" : ", ") + benchNumber(w, 3);
    os << r.runs << " | " << (r.wall_s <= r.target_s ? "" : "**") << benchNumber(r.wall_s, 3)
       << " s" << (r.wall_s <= r.target_s ? "" : "**") << " | <= " << benchNumber(r.target_s, 6)
       << " s: " << (r.wall_s <= r.target_s ? "met" : "NOT met") << " | " << benchNumber(r.cpu_s, 3)
       << " s | " << benchNumber(r.load_min, 2, Notation::Fixed) << "-"
       << benchNumber(r.load_max, 2, Notation::Fixed) << " | " << each << " s |\n";
  }
  os << "\nMade by (each with `--out DIR`):\n\n";
  for (const MapRow& r : rows) os << "    " << r.command << "\n";
  return os.str();
}

}  // namespace metrosync::bench
