// The summary of one run of tools/bench/speed.sh (issue 23), from the files it wrote in one
// folder (docs/bench/speed/): ratios.csv and nslope.csv (metrosync_bench precision against the
// careful peer), verdicts.md, run.csv and run.md (`run` against its engine), maps.csv and
// maps.md (the two maps), and provenance.md (the script's: date, commit, machine, load, commands).
// From them: the paragraph that README.md's speed section carries between two marker comments, and
// the folder's README.md. Missing parts (no peer, maps skipped) are said in the text, never
// invented.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/speed_inputs.h"

namespace metrosync::bench {

// The marker comments around the generated paragraph in README.md.
extern const char* const kSpeedBegin;
extern const char* const kSpeedEnd;

// The numbers the paragraph quotes (NaN / 0 where the part is missing).
struct SpeedFacts {
  struct Group {  // the ratio cells of the scenes with N metronomes (final-state error, CPU)
    int n = 0;
    int cells = 0, met = 0;
    double lo = 0.0, hi = 0.0;  // smallest and largest filled ratio
  };
  std::vector<Group> groups;          // by N
  double err_lo = 0.0, err_hi = 0.0;  // the errors of the table's columns
  int scenes = 0;
  double slope_lo = 0.0, slope_hi = 0.0;  // metrosync's N-slope over the slope errors
  int slope_n_lo = 0, slope_n_hi = 0;
  // the default rig (yaml/rigs/experiment.yaml) as `run` runs it, if measured (NaN otherwise)
  double default_wall = 0.0, default_engine = 0.0, default_process = 0.0;
  int run_rows = 0, run_met = 0, run_inconsistent = 0;  // impossible engine/wall splits
  double run_ratio_lo = 0.0, run_ratio_hi = 0.0, run_target = 0.0;
  double full_map_s = 0.0, slow_map_s = 0.0;  // NaN: not run
  double full_target_s = 0.0, slow_target_s = 0.0;
  double load_lo = 0.0, load_hi = 0.0;  // over every timed point of every part
};

// Throws std::invalid_argument (file, line, what) for a malformed CSV.
SpeedFacts speedFacts(const SpeedInputs& in);

// The README paragraph (Markdown, no markers).
std::string speedParagraph(const SpeedFacts& f, const SpeedInputs& in);

// docs/bench/speed/README.md: the paragraph, provenance, the verdicts, the tables of `run` and
// the maps, and what each file holds.
std::string speedPage(const SpeedFacts& f, const SpeedInputs& in);

// `text` with everything between the line holding `begin` and the line holding `end` replaced by
// `block` (the marker lines kept). Throws std::invalid_argument when either marker is missing,
// appears twice, or the end comes first.
std::string replaceBetweenMarkers(const std::string& text, const std::string& begin,
                                  const std::string& end, const std::string& block);

}  // namespace metrosync::bench
