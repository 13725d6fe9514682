#include "sim/record/envelope_csv.h"

#include <stdexcept>

namespace metrosync {

EnvelopeCsvReader::EnvelopeCsvReader(const std::string& path) : in_(path), lines_(in_, path) {
  if (!in_) throw std::runtime_error(path + ": cannot open");
  if (!lines_.next(cells_)) throw std::runtime_error(path + ": empty file");
  layout_ = parseEnvelopeHeader(lines_.text(), path);  // with or without the r column
}

bool EnvelopeCsvReader::next(EnvelopeRow& row) {
  if (!lines_.next(cells_)) return false;
  if (static_cast<int>(cells_.size()) != layout_.columns())
    lines_.fail("wrong number of columns (" + std::to_string(cells_.size()) + ", the header has " +
                std::to_string(layout_.columns()) + ")");
  values_.clear();
  for (const std::string& cell : cells_) {
    const std::optional<double> v = csvNumber(cell);
    if (!v) lines_.fail("bad number '" + cell + "'");
    values_.push_back(*v);
  }
  row = envelopeRowFromValues(values_, layout_);
  return true;
}

std::vector<EnvelopeRow> readEnvelopeCsv(const std::string& path) {
  EnvelopeCsvReader reader(path);
  std::vector<EnvelopeRow> rows;
  for (EnvelopeRow row; reader.next(row);) rows.push_back(row);
  return rows;
}

}  // namespace metrosync
