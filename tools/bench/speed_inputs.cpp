#include "tools/bench/speed_inputs.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace metrosync::bench {

const char* const kDefaultRig = "default";
const char* const kDefaultRigFile = "yaml/rigs/experiment.yaml";

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) return "";
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

SpeedInputs readSpeedInputs(const std::string& dir) {
  const std::filesystem::path d(dir);
  SpeedInputs in;
  in.ratios_csv = slurp(d / "ratios.csv");
  in.nslope_csv = slurp(d / "nslope.csv");
  in.verdicts_md = slurp(d / "verdicts.md");
  in.run_csv = slurp(d / "run.csv");
  in.maps_csv = slurp(d / "maps.csv");
  in.run_md = slurp(d / "run.md");
  if (std::filesystem::is_directory(d))
    for (const auto& e : std::filesystem::directory_iterator(d)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("wp-", 0) == 0 && name.size() > 4 &&
          name.compare(name.size() - 4, 4, ".csv") == 0 &&
          name.find("-equal-error.csv") == std::string::npos)
        in.wp_csvs.push_back(slurp(e.path()));
    }
  in.maps_md = slurp(d / "maps.md");
  in.provenance_md = slurp(d / "provenance.md");
  in.runpoints_csv = slurp(d / "runpoints.csv");
  in.process_csv = slurp(d / "process.csv");
  in.process_md = slurp(d / "process.md");
  in.eventcost_csv = slurp(d / "eventcost.csv");
  in.eventcost_md = slurp(d / "eventcost.md");
  in.fit_csv = slurp(d / "fit.csv");
  in.fit_md = slurp(d / "fit.md");
  in.continuation_csv = slurp(d / "continuation.csv");
  in.continuation_md = slurp(d / "continuation.md");
  in.peer = slurp(d / "peer.md");
  while (!in.peer.empty() && (in.peer.back() == '\n' || in.peer.back() == ' ')) in.peer.pop_back();
  return in;
}

}  // namespace metrosync::bench
