#include "tools/bench/csv_table.h"

#include <limits>
#include <sstream>
#include <stdexcept>

#include "tools/bench/wp_csv.h"

namespace metrosync::bench {

bool CsvTable::has(const std::string& key) const {
  return !rows.empty() && rows.front().count(key) > 0;
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
  return csvNumber(text(row, key), source + " line " + std::to_string(row + 2) + ", column " + key);
}

CsvTable parseCsvTable(const std::string& text, const std::string& source) {
  CsvTable csv;
  csv.source = source;
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) return csv;
  const std::vector<std::string> header = csvCellsAt(line, source + " line 1");
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
  }
  return csv;
}

}  // namespace metrosync::bench
