#include "tools/bench/csv_table.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "base/csv.h"

namespace metrosync::bench {

namespace {

// The fields of one CSV line (base/csv.h csvCells); an unterminated quote throws
// std::invalid_argument "WHERE: unterminated quote".
std::vector<std::string> csvCellsAt(const std::string& line, const std::string& where) {
  try {
    return csvCells(line);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": " + e.what());
  }
}

}  // namespace

double csvNumber(const std::string& s, const std::string& where) {
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::optional<double> v = metrosync::csvNumber(s);
  if (!v) throw std::invalid_argument(where + ": '" + s + "' is not a number");
  return *v;
}

bool CsvTable::has(const std::string& key) const {
  return std::find(columns.begin(), columns.end(), key) != columns.end();
}

const std::string& CsvTable::text(size_t row, const std::string& key) const {
  const auto it = rows[row].find(key);
  if (it == rows[row].end()) throw std::invalid_argument(source + ": no column '" + key + "'");
  return it->second;
}

std::string CsvTable::textOr(size_t row, const std::string& key,
                             const std::string& fallback) const {
  const auto it = rows[row].find(key);
  return it == rows[row].end() ? fallback : it->second;
}

double CsvTable::number(size_t row, const std::string& key) const {
  return csvNumber(text(row, key),
                   source + " line " + std::to_string(lines[row]) + ", column " + key);
}

CsvTable parseCsvTable(const std::string& text, const std::string& source) {
  CsvTable csv;
  csv.source = source;
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) return csv;
  const std::vector<std::string> header = csvCellsAt(line, source + " line 1");
  csv.columns = header;
  for (int lineno = 2; std::getline(in, line); ++lineno) {
    if (line.empty()) continue;
    const std::vector<std::string> f = csvCellsAt(line, source + " line " + std::to_string(lineno));
    if (f.size() != header.size())
      throw std::invalid_argument(source + " line " + std::to_string(lineno) + ": " +
                                  std::to_string(f.size()) + " fields, the header has " +
                                  std::to_string(header.size()));
    std::map<std::string, std::string> row;
    for (size_t k = 0; k < f.size(); ++k) row[header[k]] = f[k];
    csv.rows.push_back(row);
    csv.lines.push_back(lineno);
  }
  return csv;
}

}  // namespace metrosync::bench
