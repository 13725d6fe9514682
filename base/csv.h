// The one CSV reader: every CSV file the project reads goes through it (envelope.csv read back by
// `compare` and the tests, measured data for `fit`, a sweep's regimes.csv when merged or resumed,
// the bench's tables). Cells are split as RFC 4180 says (a cell that starts with a quote runs to
// the closing quote, "" inside it is one quote); a line's trailing '\r' is dropped, so files
// written on Windows read the same. Errors name the file and the line: "FILE:LINE: what".
#pragma once

#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace metrosync {

// What is wrong in a CSV file, where: what() is "FILE:LINE: what" (LINE 1 is the header's).
struct CsvError : std::runtime_error {
  CsvError(const std::string& file, long line, const std::string& what);
  std::string file;
  long line;
};

// The cells of one line. Throws std::invalid_argument("unterminated quote") when a quoted cell
// does not end on the line.
std::vector<std::string> csvCells(std::string_view line);

// A cell as a number: the whole cell, as strtod reads it (so "nan" and "inf" too); nothing when
// the cell is empty or is not a number throughout.
std::optional<double> csvNumber(std::string_view cell);

// The lines of a CSV stream with their numbers, split into cells.
class CsvLines {
 public:
  CsvLines(std::istream& in, std::string file);
  // The next line that is not empty, split; false at the end. Throws CsvError on an
  // unterminated quote.
  bool next(std::vector<std::string>& cells);
  long line() const { return line_; }                // the number of the line last read
  const std::string& text() const { return text_; }  // that line, without its '\r'
  // Throws CsvError at the line last read.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::istream& in_;
  std::string file_, text_;
  long line_ = 0;
};

}  // namespace metrosync
