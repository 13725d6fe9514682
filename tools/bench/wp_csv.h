// Reads metrosync_bench's work-precision CSV (tools/bench/bench_report.h, csvHeader) back into the
// values the peer verdict needs, so that the verdict of a run and the one recomputed from its
// files are the same computation.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/peer_verdict.h"

namespace metrosync::bench {

// One VerdictScene per scene in `text` (a wp-*.csv: one scene). `source` names the text in
// errors. Rows of engines other than the two sides are ignored. Throws std::invalid_argument
// (source, line, column, what is wrong) for a missing column or a malformed number.
std::vector<VerdictScene> parseWorkPrecisionCsv(const std::string& text, const std::string& source,
                                                const Sides& sides = {});

// The fields of one CSV line (base/csv.h csvCells); an unterminated quote throws
// std::invalid_argument "WHERE: unterminated quote".
std::vector<std::string> csvCellsAt(const std::string& line, const std::string& where);

// A CSV field as a number: NaN when empty; throws std::invalid_argument "WHERE: 'S' is not a
// number" when it is not one (WHERE: file, line and column).
double csvNumber(const std::string& s, const std::string& where);

}  // namespace metrosync::bench
