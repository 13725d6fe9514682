// The bench's scenes (yaml/rigs/bench/NAME.yaml) as the tests of tests/bench find them.
#pragma once

#include <string>

namespace metrosync::testing_support {

inline std::string benchRig(const std::string& name) {
  return std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/bench/" + name + ".yaml";
}

}  // namespace metrosync::testing_support
