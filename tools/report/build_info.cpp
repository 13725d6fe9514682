#include "tools/report/build_info.h"

#include <Eigen/Core>

#include "sim/record/atomic_file.h"

namespace metrosync {

namespace {

// the Simbody library the plugin is linked with, as it reported itself at configure time
// (CMakeLists.txt): asking it at run time would load Simbody into every process
std::string simbodyVersion() {
  return METROSYNC_SIMBODY_VERSION;
}

std::vector<std::string>& commandLineStore() {
  static std::vector<std::string> args;
  return args;
}

}  // namespace

const BuildInfo& buildInfo() {
  static const BuildInfo info{metrosyncVersion(), gitCommit(), simbodyVersion(),
                              std::to_string(EIGEN_WORLD_VERSION) + "." +
                                  std::to_string(EIGEN_MAJOR_VERSION) + "." +
                                  std::to_string(EIGEN_MINOR_VERSION)};
  return info;
}

nlohmann::json buildJson() {
  const BuildInfo& b = buildInfo();
  return {
      {"metrosync", b.metrosync}, {"commit", b.commit}, {"simbody", b.simbody}, {"eigen", b.eigen}};
}

std::string versionText() {
  const BuildInfo& b = buildInfo();
  return b.metrosync + "\ncommit " + b.commit + "\nSimbody " + b.simbody + ", Eigen " + b.eigen;
}

void setCommandLine(int argc, const char* const* argv) {
  std::vector<std::string>& args = commandLineStore();
  args.clear();
  for (int k = 0; k < argc; ++k) args.emplace_back(argv[k] ? argv[k] : "");
}

const std::vector<std::string>& commandLine() {
  return commandLineStore();
}

}  // namespace metrosync
