// Sensible-range warnings of a physical rig (yaml/sensible_ranges.h, docs/sensible-ranges.md) as
// every command that reads a rig says them: one warning on stderr per value outside its range,
// or with --strict the first of them as an error (exit 2, before anything is written).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace metrosync::cli {

// --strict on `cmd`, into `strict`.
CLI::Option* addStrictFlag(CLI::App* cmd, bool& strict);

// Says the rig's values outside their ranges ("metrosync: warning: ...") or, with `strict`,
// throws RigError with the first. `text`: the rig's YAML; `display_name` and `sets` as loaded.
void checkSensibleRanges(const std::string& text, const std::string& display_name,
                         const std::vector<std::string>& sets, bool strict);

}  // namespace metrosync::cli
