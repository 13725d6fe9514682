#include "tools/cli/fault_hooks.h"

namespace metrosync::cli {

FaultHooks& faultHooks() {
  static FaultHooks hooks;
  return hooks;
}

std::optional<std::string> injectedFailure(long g) {
  const FaultHooks& h = faultHooks();
  return h.fail_point ? h.fail_point(g) : std::nullopt;
}

}  // namespace metrosync::cli
