// A rig written back as YAML (docs/fit.md: `metrosync fit` writes the fitted rig this way): the
// rig file's keys after --set overrides, in the file's order, in block style. The values are the
// text they were written with (a number set by an override as its shortest exact decimal);
// comments of the original are not kept, a header comment may be given instead.
#pragma once

#include <string>
#include <vector>

namespace metrosync {

// The rig text with `overrides` ("key.path=value", as --set) applied, as YAML that loads to the
// same rig. `header`: comment lines put first (each prefixed with "# "). Throws RigError for an
// invalid rig or override, as loadRigText does.
std::string rigYamlWithOverrides(const std::string& yaml_text, const std::string& display_name,
                                 const std::vector<std::string>& overrides,
                                 const std::vector<std::string>& header = {});

// The shortest decimal text that reads back as exactly `v` (for a --set override).
std::string exactNumberText(double v);

}  // namespace metrosync
