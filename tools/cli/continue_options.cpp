#include "tools/cli/continue_options.h"

#include <memory>

#include "base/number_text.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

// The loader's message about --set KEY=VALUE of an `extra` override, said of --param.
RigError asParam(const RigError& e, const std::vector<std::string>& extra) {
  std::string what = e.what();
  for (const auto& x : extra)
    for (size_t at = what.find("--set " + x); at != std::string::npos;
         at = what.find("--set " + x, at))
      what.replace(at, 5, "--param");
  return RigError(what);
}

}  // namespace

Rig loadContinueRig(const ContinueOptions& opt, const std::vector<std::string>& extra) {
  std::vector<std::string> o = opt.sets;
  o.insert(o.end(), extra.begin(), extra.end());
  try {
    return opt.rig_path.empty() ? defaultRig(o) : loadRigFile(opt.rig_path, o);
  } catch (const RigError& e) {
    throw asParam(e, extra);
  }
}

ContinueRigAt continueRigAt(const ContinueOptions& opt, const std::vector<std::string>& keys) {
  const bool builtin = opt.rig_path.empty();
  const auto rig =
      std::make_shared<const RigAtValues>(builtin ? defaultRigYaml() : readRigFile(opt.rig_path),
                                          builtin ? "<default rig>" : opt.rig_path, opt.sets, keys);
  return [rig, keys](const std::vector<double>& values) {
    try {
      return rig->at(values);
    } catch (const RigError& e) {
      std::vector<std::string> extra;
      for (std::size_t k = 0; k < keys.size(); ++k)
        extra.push_back(keys[k] + "=" + roundTripText(values[k]));
      throw asParam(e, extra);
    }
  };
}

}  // namespace metrosync::cli
