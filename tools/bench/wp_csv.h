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

}  // namespace metrosync::bench
