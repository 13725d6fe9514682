// The sweep's files (docs: sim/analysis/sweep.h says what a sweep is): regimes.csv (one line per
// grid point, streamed as points finish), sweep.json (the manifest) and the progress line. The
// grid, the points and the scheduling are analyses and live in sim/analysis/sweep.*.
#include "tools/report/sweep_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <set>
#include <sstream>

#include "base/csv.h"
#include "base/number_text.h"
#include "sim/record/atomic_file.h"
#include "sim/record/safe_open.h"
#include "tools/report/external_sort.h"
#include "tools/report/progress_log.h"
#include "tools/report/report_numbers.h"

namespace metrosync {

namespace {

// A CSV cell: quoted (quotes doubled) when it holds a separator, a quote or a line break; line
// breaks become spaces so that every row is one line.
std::string csvCell(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// One line's cells (base/csv.h); an unterminated quote is a SweepInputError.
std::vector<std::string> regimesCells(const std::string& line) {
  try {
    return csvCells(line);
  } catch (const std::invalid_argument& e) {
    throw SweepInputError(e.what());
  }
}

// A number cell; empty (no value; "nan" in files written before issue 39) is NaN.
double cellNumber(const std::string& cell, const std::string& column) {
  if (cell.empty() || cell == "nan") return std::numeric_limits<double>::quiet_NaN();
  const std::optional<double> v = csvNumber(cell);
  if (!v) throw SweepInputError(column + " = '" + cell + "' is not a number");
  return *v;
}

// A grid index: digits only, the whole cell.
std::optional<long> indexCell(const std::string& cell) {
  long v = 0;
  const char* end = cell.data() + cell.size();
  const auto [p, ec] = std::from_chars(cell.data(), end, v);
  if (cell.empty() || ec != std::errc() || p != end || v < 0) return std::nullopt;
  return v;
}

}  // namespace

std::vector<std::string> regimesColumns(const SweepGrid& grid, int n) {
  std::vector<std::string> c;
  for (const auto& a : grid.axes()) c.push_back(a.key);
  c.push_back("regime");
  for (int i = 1; i <= n; ++i) c.push_back("A_" + std::to_string(i));
  for (int j = 2; j <= n; ++j) c.push_back("psi_" + std::to_string(j));
  for (const char* extra : {"r", "s", "clusters", "tau"}) c.push_back(extra);
  if (grid.basin().samples > 0) c.push_back("in_phase_fraction");
  for (const char* extra : {"complete", "index", "message"}) c.push_back(extra);
  return c;
}

std::string regimesHeader(const SweepGrid& grid, int n) {
  std::string h;
  for (const auto& c : regimesColumns(grid, n)) h += (h.empty() ? "" : ",") + csvCell(c);
  return h;
}

std::string formatRegimesRow(const SweepGrid& grid, const SweepPoint& p) {
  const std::vector<long> c = grid.coordinates(p.index);
  std::string s;
  for (size_t a = 0; a < c.size(); ++a) s += (a ? "," : "") + grid.axes()[a].text(c[a]);
  s += "," + csvCell(p.regime);
  // a complete point has every number but s; a failed one those it reached (the others empty)
  const auto number = [&](double v, int digits) {
    return p.complete ? numberText(v, digits) : optionalCell(v, digits);
  };
  for (double v : p.A) s += "," + number(v, 12);
  for (double v : p.psi) s += "," + number(v, 12);
  s += "," + number(p.r, 12);
  s += "," + optionalCell(p.s, 12);
  s += "," + csvCell(p.clusters);
  s += "," + number(p.tau, 10);
  if (grid.basin().samples > 0) s += "," + number(p.in_phase_fraction, 12);
  s += p.complete ? ",1" : ",0";
  s += "," + std::to_string(p.index);
  s += "," + csvCell(p.message);
  return s;
}

// ---- timings.csv --------------------------------------------------------------------------------

std::string timingsHeader() {
  return "index,wall_seconds,cpu_seconds,engine_cpu_seconds";
}

std::string formatTimingsRow(const SweepPoint& p) {
  auto cell = [](double v) { return std::isfinite(v) ? numberText(v) : std::string(); };
  return std::to_string(p.index) + "," + cell(p.wall_seconds) + "," + cell(p.cpu_seconds) + "," +
         cell(p.engine_cpu_seconds);
}

size_t resumableTimingsBytes(const std::string& path) {
  std::string text = readRegularFile(path);  // a link or FIFO at the name: refused
  if (text.empty()) return 0;
  text.resize(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);  // whole lines
  const std::string header = timingsHeader() + "\n";
  if (text.empty() || text.compare(0, header.size(), header) == 0) return text.size();
  // an older layout: its rows keep their index and wall time, the other columns empty
  const size_t columns = static_cast<size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  std::string out = header;
  std::istringstream lines(text.substr(text.find('\n') + 1));
  for (std::string line; std::getline(lines, line);) {
    size_t have = static_cast<size_t>(std::count(line.begin(), line.end(), ',')) + 1;
    if (line.empty() || have > columns) continue;
    for (; have < columns; ++have) line += ",";
    out += line + "\n";
  }
  writeFileAtomically(path, out);
  return out.size();
}

SweepPoint parseRegimesRow(const SweepGrid& grid, int n, const std::string& line) {
  const std::vector<std::string> cells = regimesCells(line);
  const std::vector<std::string> cols = regimesColumns(grid, n);
  if (cells.size() != cols.size())
    throw SweepInputError(std::to_string(cells.size()) + " columns, expected " +
                          std::to_string(cols.size()));
  size_t k = 0;
  const size_t nkeys = grid.axes().size();
  std::vector<std::string> keys(cells.begin(), cells.begin() + nkeys);
  k = nkeys;
  SweepPoint p;
  p.regime = cells[k++];
  if (p.regime.empty()) throw SweepInputError("empty regime");
  for (int i = 0; i < n; ++i, ++k) p.A.push_back(cellNumber(cells[k], cols[k]));
  for (int j = 1; j < n; ++j, ++k) p.psi.push_back(cellNumber(cells[k], cols[k]));
  p.r = cellNumber(cells[k], cols[k]);
  ++k;
  p.s = cellNumber(cells[k], cols[k]);
  ++k;
  p.clusters = cells[k++];
  p.tau = cellNumber(cells[k], cols[k]);
  ++k;
  if (grid.basin().samples > 0) {
    p.in_phase_fraction = cellNumber(cells[k], cols[k]);
    ++k;
  }
  if (cells[k] != "0" && cells[k] != "1")
    throw SweepInputError("complete = '" + cells[k] + "' is not 0 or 1");
  p.complete = cells[k++] == "1";
  const auto index = indexCell(cells[k]);
  if (!index || *index >= grid.size())
    throw SweepInputError("index = '" + cells[k] + "' is not a point of the grid (0 to " +
                          std::to_string(grid.size() - 1) + ")");
  p.index = *index;
  ++k;
  p.message = cells[k];
  const std::vector<long> c = grid.coordinates(p.index);
  for (size_t a = 0; a < nkeys; ++a)
    if (keys[a] != grid.axes()[a].text(c[a]))
      throw SweepInputError(grid.axes()[a].key + " = " + keys[a] + " is not the value of point " +
                            std::to_string(p.index) + " (" + grid.axes()[a].text(c[a]) + ")");
  return p;
}

namespace {

// The header of the regimes.csv read by `f` (its first line, without the newline); "" when the
// file has no whole line.
std::string readHeader(std::FILE* f, bool& whole) {
  std::string header;
  for (int c; (c = std::fgetc(f)) != EOF;) {
    if (c == '\n') {
      whole = true;
      return header;
    }
    header += static_cast<char>(c);
  }
  whole = false;
  return header;
}

}  // namespace

RegimesScan scanRegimesCsv(const std::string& path, const SweepGrid& grid, int n,
                           const std::string& dropped, const RegimesVisitor& visit) {
  RegimesScan t;
  const int fd = openRegularForReading(path);  // a link or FIFO at the name: refused
  if (fd < 0) return t;
  std::FILE* f = ::fdopen(fd, "r");
  if (!f) {
    ::close(fd);
    throw std::runtime_error("cannot read " + path);
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(f, &std::fclose);
  bool whole = false;
  const std::string header = readHeader(f, whole);
  if (!whole) {  // not even a whole header: start afresh
    if (!header.empty()) t.partial_lines = 1;
    return t;
  }
  const std::string expected = regimesHeader(grid, n);
  if (header != expected)
    throw SweepInputError(path + ": its header is not this sweep's:\n  found    " + header +
                          "\n  expected " + expected);
  t.complete_bytes = header.size() + 1;
  char* buf = nullptr;
  std::size_t cap = 0;
  long lineno = 1;
  for (ssize_t len; (len = ::getline(&buf, &cap, f)) > 0;) {
    if (buf[len - 1] != '\n') {
      t.partial_lines = 1;  // said first, as before any row's warning
      t.warnings.insert(t.warnings.begin(),
                        path + ": the last line was cut short (an interrupted write): dropped");
      break;
    }
    t.complete_bytes += static_cast<std::size_t>(len);
    ++lineno;
    const std::string line(buf, static_cast<std::size_t>(len - 1));
    if (line.empty()) continue;
    try {
      if (!visit(parseRegimesRow(grid, n, line), line)) ++t.duplicate_lines;
    } catch (const SweepInputError& e) {
      ++t.malformed_lines;
      t.warnings.push_back(path + ":" + std::to_string(lineno) + ": " + e.what() + ": dropped (" +
                           dropped + ")");
    }
  }
  std::free(buf);
  return t;
}

RegimesTable readRegimesCsv(const std::string& path, const SweepGrid& grid, int n,
                            const std::string& dropped) {
  RegimesTable t;
  RegimesScan& scan = t;
  scan = scanRegimesCsv(path, grid, n, dropped, [&](SweepPoint p, const std::string& line) {
    if (t.lines.count(p.index)) return false;  // the first line of an index wins
    t.lines[p.index] = line;
    t.points[p.index] = std::move(p);
    return true;
  });
  return t;
}

std::optional<long> regimesRowIndex(const SweepGrid& grid, int n, const std::string& line) {
  try {
    return parseRegimesRow(grid, n, line).index;
  } catch (const SweepInputError&) {
    return std::nullopt;  // malformed: dropped (--resume warned when it read the file)
  }
}

namespace {

// Calls line(text) for each whole line of the regimes.csv at `path` after its header (a last line
// cut short is skipped); nothing when the file is absent.
void forEachRowLine(const std::string& path, const std::function<void(std::string)>& line) {
  const int fd = openRegularForReading(path);  // a link or FIFO at the name: refused
  if (fd < 0) return;
  std::FILE* f = ::fdopen(fd, "r");
  if (!f) {
    ::close(fd);
    throw std::runtime_error("cannot read " + path);
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(f, &std::fclose);
  char* buf = nullptr;
  std::size_t cap = 0;
  bool header = true;
  for (ssize_t len; (len = ::getline(&buf, &cap, f)) > 0;) {
    if (header || buf[len - 1] != '\n') {  // the header; a last line cut short
      header = false;
      continue;
    }
    try {
      line(std::string(buf, static_cast<std::size_t>(len - 1)));
    } catch (...) {
      std::free(buf);
      throw;
    }
  }
  std::free(buf);
}

}  // namespace

void sortRegimesCsv(const std::string& path, const SweepGrid& grid, int n,
                    const std::function<bool(long)>& keep, std::size_t chunk_bytes) {
  const std::size_t slash = path.rfind('/');
  ExternalSort sort(slash == std::string::npos ? "." : path.substr(0, slash), chunk_bytes);
  forEachRowLine(path, [&](std::string line) {
    const std::optional<long> g = regimesRowIndex(grid, n, line);
    if (g && keep(*g)) sort.add(*g, std::move(line));
  });
  AtomicFile out(path);
  out.writeLine(regimesHeader(grid, n));
  sort.forEachIndex(
      [&](long, const std::vector<std::string>& lines) { out.writeLine(lines.back()); });
  out.commit();
}

void forEachRegimesRow(const std::string& path, const SweepGrid& grid, int n,
                       const std::function<void(const SweepPoint&)>& visit,
                       const std::function<bool(const std::string&)>& wanted) {
  forEachRowLine(path, [&](std::string line) {
    if (wanted && !wanted(line)) return;
    std::optional<SweepPoint> p;
    try {
      p = parseRegimesRow(grid, n, line);
    } catch (const SweepInputError&) {
      return;  // malformed: not drawn
    }
    visit(*p);
  });
}

RegimesAppender::RegimesAppender(const std::string& path, const std::string& header, bool fresh,
                                 size_t keep_bytes)
    : path_(path), check_(path) {
  check_.line(header);                      // the columns of the rows' messages
  fd_ = openOutputFile(path, fresh, true);  // never through a planted link or FIFO
  if (fresh) {
    put(header);
  } else if (::ftruncate(fd_, static_cast<off_t>(keep_bytes)) != 0) {
    const std::string why = std::strerror(errno);
    close();
    throw std::runtime_error("cannot cut " + path + " to its whole lines: " + why);
  }
}

RegimesAppender::~RegimesAppender() {
  close();
}

void RegimesAppender::append(const std::string& line) {
  check_.line(line);  // no non-finite number (sim/record/finite_check.h)
  put(line);
}

void RegimesAppender::put(const std::string& line) {
  if (fd_ < 0) throw std::logic_error("append to a closed " + path_);
  const std::string text = line + "\n";
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t w = ::write(fd_, text.data() + done, text.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
    done += static_cast<size_t>(w);
  }
}

void RegimesAppender::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

// ---- sweep.json ---------------------------------------------------------------------------------

nlohmann::json SweepManifest::toJson() const {
  return {{"command", merged ? "merge" : "sweep"},
          {"version", metrosyncVersion()},
          {"model", model},
          {"engine", engine},
          {"rig", {{"path", rig_path}, {"name", rig_name}, {"text", rig_text}}},
          {"sets", sets},
          {"metronomes", metronomes},
          {"grid", grid.toJson()},
          {"shard", {{"k", shard.k}, {"n", shard.n}}}};
}

SweepManifest SweepManifest::fromJson(const nlohmann::json& j) {
  try {
    SweepManifest m;
    m.merged = j.at("command").get<std::string>() == "merge";
    m.model = j.at("model").get<std::string>();
    m.engine = j.at("engine").get<std::string>();
    m.rig_path = j.at("rig").at("path").get<std::string>();
    m.rig_name = j.at("rig").at("name").get<std::string>();
    m.rig_text = j.at("rig").at("text").get<std::string>();
    m.sets = j.at("sets").get<std::vector<std::string>>();
    m.metronomes = j.at("metronomes").get<int>();
    m.grid = SweepGrid::fromJson(j.at("grid"));
    m.shard.k = j.at("shard").at("k").get<int>();
    m.shard.n = j.at("shard").at("n").get<int>();
    if (m.metronomes < 1 || m.shard.n < 1 || m.shard.k < 1 || m.shard.k > m.shard.n)
      throw SweepInputError("metronomes or shard out of range");
    return m;
  } catch (const nlohmann::json::exception& e) {
    throw SweepInputError(std::string("not a sweep manifest: ") + e.what());
  }
}

std::string sweepDifference(const SweepManifest& a, const SweepManifest& b) {
  if (a.model != b.model) return "the model differs (" + a.model + " / " + b.model + ")";
  if (a.engine != b.engine) return "the engine differs (" + a.engine + " / " + b.engine + ")";
  if (a.rig_text != b.rig_text) return "the rig differs (its text is not the same)";
  if (a.sets != b.sets) return "the --set overrides differ";
  if (a.metronomes != b.metronomes) return "the number of metronomes differs";
  const auto &x = a.grid.axes(), &y = b.grid.axes();
  if (x.size() != y.size()) return "the number of --vary differs";
  for (size_t k = 0; k < x.size(); ++k) {
    if (x[k].key != y[k].key) return "--vary " + x[k].key + " / --vary " + y[k].key;
    if (!x[k].sameValues(y[k]))
      return "--vary " + x[k].key + "=" + x[k].spec + " / " + y[k].spec + ": other values";
  }
  if (!(a.grid.basin() == b.grid.basin())) return "--basin-samples, --random or --seed differ";
  return "";
}

nlohmann::json readSweepJson(const std::string& path) {
  std::string text;
  try {
    text = readRegularFile(path);  // a link or FIFO at the name: refused
  } catch (const std::runtime_error& e) {
    throw SweepInputError(e.what());
  }
  if (text.empty()) throw SweepInputError(path + ": cannot read (not a sweep output directory?)");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw SweepInputError(path + ": not valid JSON: " + e.what());
  }
}

SweepManifest readSweepManifest(const std::string& dir) {
  const std::string path = dir + "/sweep.json";
  try {
    return SweepManifest::fromJson(readSweepJson(path));
  } catch (const SweepInputError& e) {
    const std::string what = e.what();
    throw SweepInputError(what.rfind(path, 0) == 0 ? what : path + ": " + what);
  }
}

std::string progressText(long done, long total, long failed, double rate_per_s, double eta_s,
                         int width) {
  char buf[160];
  std::string eta = "ETA --:--";
  if (eta_s >= 0 && std::isfinite(eta_s)) eta = "ETA " + clockText(eta_s);
  const double pct = total > 0 ? 100.0 * static_cast<double>(done) / total : 100.0;
  std::string rate;
  if (rate_per_s > 0 && std::isfinite(rate_per_s))
    rate = rate_per_s >= 1 ? "  " + numberText(rate_per_s, 3) + " points/s"
                           : "  " + numberText(1.0 / rate_per_s, 3) + " s/point";
  std::snprintf(buf, sizeof buf, "  %ld/%ld  %3.0f%%", done, total, pct);
  std::string tail = buf + rate + "  " + eta;
  if (failed > 0) tail += "  " + std::to_string(failed) + " failed";
  const int bar = std::max(10, width - static_cast<int>(tail.size()) - 2);
  const int filled = total > 0 ? static_cast<int>(bar * static_cast<double>(done) / total) : bar;
  return "[" + std::string(std::min(filled, bar), '#') +
         std::string(bar - std::min(filled, bar), '-') + "]" + tail;
}

}  // namespace metrosync
