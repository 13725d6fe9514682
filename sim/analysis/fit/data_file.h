// Measured data for `metrosync fit` and `metrosync measure` (docs/fit.md): a CSV file with a
// header line naming its columns -- `t` (seconds, strictly increasing), and any of `theta_1` ..
// `theta_N` (rad) and `x` (m) -- one row per sample at any rate. An empty cell is a missing
// sample; every other cell must be a finite number. Lines starting with '#' are comments. The
// columns metrosync's own trajectory.csv adds (xdot, thetadot_i, platform, t_s) are read past, so
// that a run's output can be fitted as is; any other name is an error.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace metrosync {

// What is wrong with a data file; what() is "FILE:LINE: what is wrong" (LINE 1-based; no line
// when the whole file is meant).
struct DataError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One observed quantity: theta_i of metronome `metronome` (0-based), or the platform's x
// (metronome = -1).
struct DataColumn {
  std::string name;            // as in the header: "theta_2", "x"
  int metronome = -1;          // 0-based metronome index; -1 for x
  std::vector<double> values;  // (rows x 1), NaN where the sample is missing
  int present() const;         // number of samples that are not missing
};

struct MeasuredData {
  std::string path;                 // for messages
  std::vector<double> t_s;          // (rows x 1) seconds, strictly increasing
  std::vector<DataColumn> columns;  // in header order
  const DataColumn* find(const std::string& name) const;
};

// Reads and checks `path`. n_metronomes: how many the rig has (a theta_k or thetadot_k column
// with k > n_metronomes is an error); 0 = not checked. Throws DataError.
MeasuredData readDataFile(const std::string& path, int n_metronomes);

// The same for text already read (`display_name` stands for the file in messages).
MeasuredData parseDataText(const std::string& text, const std::string& display_name,
                           int n_metronomes);

}  // namespace metrosync
