// A CSV the bench wrote (a header line, then rows; fields double-quoted where they hold a comma
// or a quote) read back as rows of named fields, for the speed summary (speed_summary.h,
// speed_figures.h).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace metrosync::bench {

struct CsvTable {
  std::vector<std::string> columns;  // the header's
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<int> lines;                  // each row's line in the file, for messages
  std::string source;                      // the file's name, for messages
  bool has(const std::string& key) const;  // the header has that column
  // the field as a number: NaN when empty; throws std::invalid_argument (source, line, column)
  // when the column is missing or the field is not a number
  double number(size_t row, const std::string& key) const;
  // throws std::invalid_argument when the column is missing
  const std::string& text(size_t row, const std::string& key) const;
  // the field, or `fallback` when the column is missing (files of earlier versions)
  std::string textOr(size_t row, const std::string& key, const std::string& fallback) const;
};

// A CSV field as a number: NaN when empty; throws std::invalid_argument "WHERE: 'S' is not a
// number" when it is not one (WHERE: file, line and column).
double csvNumber(const std::string& s, const std::string& where);

// Throws std::invalid_argument (source, line, what) for a line whose field count differs from
// the header's. An empty text is an empty table.
CsvTable parseCsvTable(const std::string& text, const std::string& source);

}  // namespace metrosync::bench
