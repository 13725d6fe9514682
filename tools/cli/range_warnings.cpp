#include "tools/cli/range_warnings.h"

#include <iostream>

#include "yaml/rig_error.h"
#include "yaml/sensible_ranges.h"
#include "yaml/utf8.h"

namespace metrosync::cli {

CLI::Option* addStrictFlag(CLI::App* cmd, bool& strict) {
  return cmd->add_flag("--strict", strict,
                       "a physical rig's value outside the range of real tabletop metronomes "
                       "and boards (a unit typed wrong, e.g. millimetres for metres) is an error "
                       "(exit 2) instead of a warning; docs/sensible-ranges.md");
}

void checkSensibleRanges(const std::string& text, const std::string& display_name,
                         const std::vector<std::string>& sets, bool strict) {
  const std::vector<RangeFinding> found = sensibleRangeFindings(text, display_name, sets);
  if (found.empty()) return;
  if (strict) {
    const std::size_t more = found.size() - 1;
    throw RigError(found.front().message + "; an error with --strict" +
                   (more ? " (and " + std::to_string(more) + " more value" + (more > 1 ? "s" : "") +
                               " outside their ranges)"
                         : std::string()));
  }
  for (const RangeFinding& f : found)
    std::cerr << "metrosync: warning: " << terminalText(f.message) << "\n";
}

}  // namespace metrosync::cli
