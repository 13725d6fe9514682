#include "tools/cli/continue_options.h"

#include "yaml/rig_loader.h"

namespace metrosync::cli {

Rig loadContinueRig(const ContinueOptions& opt, const std::vector<std::string>& extra) {
  std::vector<std::string> o = opt.sets;
  o.insert(o.end(), extra.begin(), extra.end());
  try {
    return opt.rig_path.empty() ? defaultRig(o) : loadRigFile(opt.rig_path, o);
  } catch (const RigError& e) {
    std::string what = e.what();
    for (const auto& x : extra)
      for (size_t at = what.find("--set " + x); at != std::string::npos;
           at = what.find("--set " + x, at))
        what.replace(at, 5, "--param");
    throw RigError(what);
  }
}

}  // namespace metrosync::cli
