#include "sim/record/finite_check.h"

#include <cctype>

namespace metrosync {

namespace {

bool equalsLower(std::string_view s, std::string_view lower) {
  if (s.size() != lower.size()) return false;
  for (std::size_t k = 0; k < s.size(); ++k)
    if (std::tolower(static_cast<unsigned char>(s[k])) != lower[k]) return false;
  return true;
}

// Calls cell(index, text) for each cell of `line` (quotes kept; a quoted cell is text, never a
// number) until it returns false.
template <class F>
void forEachCell(std::string_view line, F cell) {
  std::size_t start = 0, index = 0;
  bool quoted = false;
  for (std::size_t k = 0; k <= line.size(); ++k) {
    if (k < line.size() && line[k] == '"') quoted = !quoted;
    if (k < line.size() && (quoted || line[k] != ',')) continue;
    if (!cell(index++, line.substr(start, k - start))) return;
    start = k + 1;
  }
}

// Can `line` hold a non-finite number at all? Each of them has an n or an i (nan, inf,
// infinity, any case); a row of numbers as %g writes them has neither, and is passed by this one
// scan without being split into cells.
bool mayHoldNonFinite(std::string_view line) {
  for (const char c : line)
    if (c == 'n' || c == 'N' || c == 'i' || c == 'I') return true;
  return false;
}

}  // namespace

bool isNonFiniteText(std::string_view cell) {
  if (!cell.empty() && (cell[0] == '-' || cell[0] == '+')) cell.remove_prefix(1);
  if (cell.size() < 3) return false;
  const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(cell[0])));
  if (c != 'n' && c != 'i') return false;  // the common case: a number or a word
  if (equalsLower(cell, "inf") || equalsLower(cell, "infinity") || equalsLower(cell, "nan"))
    return true;
  // nan(chars): strtod's NaN with a payload
  return cell.size() > 4 && equalsLower(cell.substr(0, 4), "nan(") && cell.back() == ')';
}

void CsvCheck::line(std::string_view line) {
  if (row_ < 0) {
    forEachCell(line, [&](std::size_t, std::string_view name) {
      columns_.emplace_back(name);
      return true;
    });
    row_ = 0;
    return;
  }
  ++row_;
  if (!mayHoldNonFinite(line)) return;
  forEachCell(line, [&](std::size_t index, std::string_view cell) {
    if (!isNonFiniteText(cell)) return true;
    const std::string column =
        index < columns_.size() ? columns_[index] : "number " + std::to_string(index + 1);
    throw NonFiniteOutput(file_ + ": row " + std::to_string(row_) + ", column " + column + ": " +
                          std::string(cell) +
                          " is not a finite number (a cell with no value is empty)");
  });
}

void CsvCheck::passed(long rows) {
  if (row_ < 0 || !pending_.empty())
    throw std::logic_error(file_ + ": rows passed unread before the header or within a line");
  row_ += rows;
}

void CsvCheck::text(std::string_view text) {
  for (;;) {
    const std::size_t nl = text.find('\n');
    if (nl == std::string_view::npos) break;
    if (pending_.empty()) {
      line(text.substr(0, nl));
    } else {
      pending_.append(text.substr(0, nl));
      line(pending_);
      pending_.clear();
    }
    text.remove_prefix(nl + 1);
  }
  pending_.append(text);
}

}  // namespace metrosync
