// How this metrosync was built and how it was called, for `metrosync --version` and the
// reproducibility keys of summary.json (docs/outputs.md): the version, the git commit (embedded
// at build time by tools/report/git_commit.cmake; "unknown" outside a git work tree), the
// Simbody and Eigen versions, and the process's command line.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace metrosync {

struct BuildInfo {
  std::string metrosync;  // the project version (CMake's PROJECT_VERSION)
  std::string commit;     // full git hash, "-dirty" appended for a modified tree; or "unknown"
  std::string simbody;  // the Simbody library the plugin links (its own report, at configure time)
  std::string eigen;    // the Eigen headers compiled against
};

const BuildInfo& buildInfo();

// The commit alone (a source generated at build time: build/generated/git_commit.cpp).
const char* gitCommit();

// {"metrosync", "commit", "simbody", "eigen"}
nlohmann::json buildJson();

// What `metrosync --version` prints: the version on the first line (man page generator), then the
// commit and the libraries.
std::string versionText();

// The process's arguments (argv[0] included), recorded once by the command line.
void setCommandLine(int argc, const char* const* argv);
const std::vector<std::string>& commandLine();

}  // namespace metrosync
