// No non-finite number in an output file (issue 39): the one check at the writers. Every CSV file
// metrosync writes goes through AtomicFile (sim/record/atomic_file.h) or, for regimes.csv and
// timings.csv, through RegimesAppender (tools/report/sweep_files.h); both check each row with a
// CsvCheck as it is written, but for a run's trajectory and event rows, whose writer checks each
// number as a double where it formats it (tools/report/deferred_rows.h) and hands CsvCheck only a
// block that holds a non-finite one. JSON files are checked as a tree before they are dumped
// (tools/report/json_file.h: nlohmann would write a NaN as null). A cell with no value is empty;
// a non-finite number where a value belongs is a failure (exit 3), named by file, row and column.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace metrosync {

// A non-finite number on its way into an output file. what(): "FILE: row R, column C: nan is not
// a finite number (a cell with no value is empty)".
struct NonFiniteOutput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Is `cell` a non-finite number as printf, iostreams or strtod write one: nan, inf, infinity,
// any case, with a sign, "nan(...)"?
bool isNonFiniteText(std::string_view cell);

// The rows of one CSV file as they are written: its first line is the header (its names say which
// column a message means), every later line a row none of whose cells may be a non-finite number.
// Cells are split at commas outside double quotes (RFC 4180, as the files quote them).
class CsvCheck {
 public:
  explicit CsvCheck(std::string file) : file_(std::move(file)) {}
  // one whole line, without its newline
  void line(std::string_view line);
  // any text: its whole lines checked, a last part without a newline kept for the next call
  void text(std::string_view text);
  // `rows` whole rows its writer has checked as numbers (after the header, no part line pending):
  // counted, so that a row checked later is still named by its place in the file
  void passed(long rows);

 private:
  std::string file_;
  std::vector<std::string> columns_;
  long row_ = -1;  // -1: the header comes next
  std::string pending_;
};

}  // namespace metrosync
