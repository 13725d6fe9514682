#include "sim/analysis/fit/data_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "base/csv.h"
#include "base/number_text.h"

namespace metrosync {

namespace {

// A data file is a few columns of samples: 64 MiB is two million rows of a 240 fps camera (2.3 h)
// with three columns, or a 200 s trajectory.csv of 32 metronomes three times over; the text and
// its parsed columns then stay below ~200 MB (a typo'd path to a huge file must not fill the
// memory).
constexpr std::uintmax_t kMaxDataFileBytes = std::uintmax_t(64) << 20;
// One line: a row of 1000 metronomes' theta and thetadot columns at 20 bytes a number is 40 kB.
constexpr std::size_t kMaxDataLineBytes = std::size_t(64) << 10;
// The record's length (last t - first t): every model run of a fit integrates over it. 10^5 s
// (28 h) is far beyond a camera record; one stray row at t = 1e9 s would otherwise send every
// model run of the fit to it (issue 29).
constexpr double kMaxRecordSeconds = 1e5;
// Fewer rows cannot determine anything.
constexpr std::size_t kMinRows = 3;

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  throw DataError(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what);
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\"");
  return s.substr(b, e - b + 1);
}

// A line's cells (base/csv.h), each trimmed of spaces: measured data typed by hand or exported by
// a spreadsheet may pad them.
std::vector<std::string> cells(const std::string& line, const std::string& file, int lineno) {
  std::vector<std::string> out;
  try {
    out = csvCells(line);
  } catch (const std::invalid_argument& e) {
    fail(file, lineno, e.what());
  }
  for (std::string& c : out) c = trimmed(c);
  return out;
}

// The k of "prefix<k>" (1-based), or 0 when `name` is not of that form.
int indexAfter(const std::string& name, const std::string& prefix) {
  if (name.compare(0, prefix.size(), prefix) != 0 || name.size() == prefix.size()) return 0;
  const std::string digits = name.substr(prefix.size());
  if (digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::stoi(digits);
}

// What a header column is: the time, an observed column, or one of metrosync's own outputs.
enum class Role { Time, Observed, Ignored };

Role roleOf(const std::string& name, int n_metronomes, const std::string& file, int& metronome) {
  metronome = -1;
  if (name == "t") return Role::Time;
  if (name == "x") return Role::Observed;
  if (name == "xdot" || name == "platform" || name == "t_s") return Role::Ignored;
  for (const char* prefix : {"theta_", "thetadot_"}) {
    const int k = indexAfter(name, prefix);
    if (k == 0) continue;
    if (n_metronomes > 0 && k > n_metronomes)
      fail(file, 1,
           "column " + name + ": the rig has " + std::to_string(n_metronomes) + " metronome" +
               (n_metronomes == 1 ? "" : "s") + " (theta_1 .. theta_" +
               std::to_string(n_metronomes) + ")");
    metronome = k - 1;
    return std::string(prefix) == "theta_" ? Role::Observed : Role::Ignored;
  }
  fail(file, 1,
       "column '" + name +
           "': unknown (expected t, theta_1 .. theta_N in rad, x in m; also read past: xdot, "
           "thetadot_i, platform, t_s)");
}

struct Header {
  int t_index = -1;
  std::vector<int> observed_index;  // cell index of each observed column
};

Header readHeader(const std::string& line, const std::string& file, int n_metronomes,
                  MeasuredData& data) {
  const std::vector<std::string> names = cells(line, file, 1);
  Header h;
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (names[j] == names[i]) fail(file, 1, "column '" + names[i] + "' appears twice");
    int metronome = -1;
    const Role role = roleOf(names[i], n_metronomes, file, metronome);
    if (role == Role::Time) h.t_index = static_cast<int>(i);
    if (role != Role::Observed) continue;
    h.observed_index.push_back(static_cast<int>(i));
    data.columns.push_back(DataColumn{names[i], metronome, {}});
  }
  if (h.t_index < 0) fail(file, 1, "no column 't' (time in seconds) in the header");
  if (data.columns.empty())
    fail(file, 1, "no data column: expected theta_1 .. theta_N (rad) or x (m)");
  return h;
}

void readRow(const std::string& line, int lineno, std::size_t n_cells, const Header& h,
             const std::string& file, MeasuredData& data) {
  const std::vector<std::string> c = cells(line, file, lineno);
  if (c.size() != n_cells)
    fail(file, lineno,
         std::to_string(c.size()) + " cells, the header has " + std::to_string(n_cells));
  const std::optional<double> t = csvNumber(c[h.t_index]);
  if (!t || !std::isfinite(*t))
    fail(file, lineno, "t = '" + c[h.t_index] + "': must be a finite number (seconds)");
  if (!data.t_s.empty() && !(*t > data.t_s.back())) {
    std::ostringstream os;
    os.precision(10);
    os << "t = " << *t << " is not after the previous row's t = " << data.t_s.back()
       << " (time must increase strictly)";
    fail(file, lineno, os.str());
  }
  data.t_s.push_back(*t);
  for (std::size_t k = 0; k < h.observed_index.size(); ++k) {
    const std::string& cell = c[h.observed_index[k]];
    DataColumn& col = data.columns[k];
    if (cell.empty()) {
      col.values.push_back(kMissing);
      continue;
    }
    const std::optional<double> v = csvNumber(cell);
    if (!v || !std::isfinite(*v))
      fail(file, lineno,
           col.name + " = '" + cell +
               "': must be a finite number (leave the cell empty for a missing sample)");
    col.values.push_back(*v);
  }
}

// A file over kMaxDataFileBytes, refused at the line where it crosses the limit (its first
// kMaxDataFileBytes read to count the lines, a fraction of a second).
[[noreturn]] void failOversized(const std::string& path, std::uintmax_t size, std::istream& in) {
  std::vector<char> chunk(std::size_t(1) << 20);
  std::uintmax_t read = 0;
  int line = 1;
  while (read < kMaxDataFileBytes && in) {
    const auto want = std::min<std::uintmax_t>(chunk.size(), kMaxDataFileBytes - read);
    in.read(chunk.data(), static_cast<std::streamsize>(want));
    const std::streamsize got = in.gcount();
    line += static_cast<int>(std::count(chunk.data(), chunk.data() + got, '\n'));
    read += static_cast<std::uintmax_t>(got);
  }
  fail(path, line,
       "the file passes " + std::to_string(kMaxDataFileBytes) +
           " bytes (64 MiB) on this line; it has " + std::to_string(size) +
           ": not a data file of samples (docs/rig-limits.md)");
}

}  // namespace

int DataColumn::present() const {
  int n = 0;
  for (double v : values) n += !std::isnan(v);
  return n;
}

const DataColumn* MeasuredData::find(const std::string& name) const {
  for (const DataColumn& c : columns)
    if (c.name == name) return &c;
  return nullptr;
}

MeasuredData parseDataText(const std::string& text, const std::string& display_name,
                           int n_metronomes) {
  MeasuredData data;
  data.path = display_name;
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  Header header;
  std::size_t n_cells = 0;
  bool have_header = false;
  int header_line = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.size() > kMaxDataLineBytes)
      fail(display_name, lineno,
           "a line of " + std::to_string(line.size()) + " bytes (at most " +
               std::to_string(kMaxDataLineBytes) + " in a data file, docs/rig-limits.md)");
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    if (!have_header) {
      header = readHeader(line, display_name, n_metronomes, data);
      n_cells = cells(line, display_name, lineno).size();
      have_header = true;
      header_line = lineno;
      continue;
    }
    readRow(line, lineno, n_cells, header, display_name, data);
  }
  if (!have_header) fail(display_name, 0, "empty: expected a header line such as t,theta_1,x");
  if (data.t_s.size() < kMinRows)
    fail(display_name, 0,
         std::to_string(data.t_s.size()) + " data rows: at least " + std::to_string(kMinRows) +
             " are needed");
  for (const DataColumn& c : data.columns)
    if (c.present() == 0)
      fail(display_name, header_line, "column " + c.name + " has no values (every cell is empty)");
  if (data.t_s.back() - data.t_s.front() > kMaxRecordSeconds)
    fail(display_name, lineno,
         "the record runs from t = " + numberText(data.t_s.front()) + " to " +
             numberText(data.t_s.back()) + " s, longer than " +
             std::to_string(static_cast<long>(kMaxRecordSeconds)) +
             " s (docs/rig-limits.md): a stray time?");
  return data;
}

MeasuredData readDataFile(const std::string& path, int n_metronomes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) fail(path, 0, "no such file");
  if (!std::filesystem::is_regular_file(status)) fail(path, 0, "not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, "cannot be read");
  if (size > kMaxDataFileBytes) failOversized(path, size, in);
  std::ostringstream text;
  text << in.rdbuf();
  return parseDataText(text.str(), path, n_metronomes);
}

}  // namespace metrosync
