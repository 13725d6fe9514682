#include "base/csv.h"

#include <cstdlib>
#include <utility>

namespace metrosync {

CsvError::CsvError(const std::string& file_, long line_, const std::string& what)
    : std::runtime_error(file_ + (line_ > 0 ? ":" + std::to_string(line_) : std::string()) + ": " +
                         what),
      file(file_),
      line(line_) {}

std::vector<std::string> csvCells(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::vector<std::string> cells(1);
  bool quoted = false, was_quoted = false;
  for (size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    std::string& cur = cells.back();
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
        cur += '"';
        ++k;
      } else if (c == '"') {
        quoted = false;
      } else {
        cur += c;
      }
    } else if (c == '"' && cur.empty() && !was_quoted) {
      quoted = was_quoted = true;
    } else if (c == ',') {
      cells.emplace_back();
      was_quoted = false;
    } else {
      cur += c;
    }
  }
  if (quoted) throw std::invalid_argument("unterminated quote");
  return cells;
}

std::optional<double> csvNumber(std::string_view cell) {
  if (cell.empty()) return std::nullopt;
  const std::string s(cell);  // strtod needs the terminating NUL
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return std::nullopt;
  return v;
}

CsvLines::CsvLines(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

bool CsvLines::next(std::vector<std::string>& cells) {
  while (std::getline(in_, text_)) {
    ++line_;
    if (!text_.empty() && text_.back() == '\r') text_.pop_back();
    if (text_.empty()) continue;
    try {
      cells = csvCells(text_);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
    return true;
  }
  return false;
}

void CsvLines::fail(const std::string& what) const {
  throw CsvError(file_, line_, what);
}

}  // namespace metrosync
