// envelope.csv read back (`compare`, the tests), through the one CSV reader (base/csv.h): a file
// written by formatEnvelopeRow, with or without the r and t_s columns. Errors name the file and
// the line.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "base/csv.h"
#include "sim/record/envelope.h"

namespace metrosync {

// Reads an envelope.csv one row at a time.
class EnvelopeCsvReader {
 public:
  // throws std::runtime_error when the file cannot be read or its header is not an envelope's
  explicit EnvelopeCsvReader(const std::string& path);
  int n() const { return layout_.n; }
  // false at the end of the file; throws CsvError (a std::runtime_error) on a malformed line
  bool next(EnvelopeRow& row);

 private:
  std::ifstream in_;
  CsvLines lines_;
  EnvelopeLayout layout_;
  std::vector<std::string> cells_;
  std::vector<double> values_;
};

// The whole file; throws std::runtime_error on bad input.
std::vector<EnvelopeRow> readEnvelopeCsv(const std::string& path);

}  // namespace metrosync
