// What the summary of one run of tools/bench/speed.sh reads (tools/bench/speed_summary.h,
// speed_figures.h): the files the run wrote in one folder, as text.
#pragma once

#include <string>
#include <vector>

namespace metrosync::bench {

// What the summary reads, as text ("" = the file is absent).
struct SpeedInputs {
  std::string ratios_csv, nslope_csv, verdicts_md, run_csv, maps_csv, provenance_md;
  std::string run_md, maps_md;
  // issue 36's parts: `run`'s points against its engine (runpoints.csv), the whole process, the
  // cost per step and per event, one fit, `continue --all`
  std::string runpoints_csv, process_csv, process_md, eventcost_csv, eventcost_md;
  std::string fit_csv, fit_md, continuation_csv, continuation_md;
  std::string peer;                  // peer.md: the peer measured against, as the README names it
  std::vector<std::string> wp_csvs;  // every wp-<scene>.csv (their loads)
  std::string date, commit;          // of the measurement, as the script gives them
  std::string folder = "docs/bench/speed";  // the folder, as README.md links it
};

// The default rig, as run.csv names it (`metrosync run` with no rig file; earlier runs named
// its file, kDefaultRigFile).
extern const char* const kDefaultRig;
extern const char* const kDefaultRigFile;

// Reads DIR's files into SpeedInputs (absent files stay "").
SpeedInputs readSpeedInputs(const std::string& dir);

}  // namespace metrosync::bench
