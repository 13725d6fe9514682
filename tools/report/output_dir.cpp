#include "tools/report/output_dir.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "sim/record/private_dir.h"

namespace metrosync {

namespace fs = std::filesystem;

std::uint64_t overridesHash(const std::vector<std::string>& overrides) {
  std::uint64_t h = 14695981039346656037ull;
  auto add = [&h](unsigned char c) { h = (h ^ c) * 1099511628211ull; };
  for (const std::string& o : overrides) {
    for (char c : o) add(static_cast<unsigned char>(c));
    add('\n');
  }
  return h;
}

std::string defaultOutputDir(const std::string& rig_name, const std::string& command,
                             const std::vector<std::string>& overrides) {
  std::string safe;
  for (char c : rig_name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_' || c == '.';
    safe += ok ? c : '_';
  }
  if (safe.empty() || safe.find_first_not_of('.') == std::string::npos) safe = "rig";
  std::string dir = "runs/" + safe + "-" + command;
  if (!overrides.empty()) {
    char hex[24];
    std::snprintf(hex, sizeof hex, "-%08llx",
                  static_cast<unsigned long long>(overridesHash(overrides) >> 32));
    dir += hex;
  }
  return dir;
}

OutputDir::OutputDir(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw std::runtime_error("empty output directory name");
  while (path_.size() > 1 && path_.back() == '/') path_.pop_back();
  std::error_code ec;
  fs::create_directories(path_, ec);
  if (ec || !fs::is_directory(path_))
    throw std::runtime_error("cannot create the output directory " + path_ + ": " +
                             (ec ? ec.message() : "not a directory"));
}

const std::vector<std::string>& OutputDir::outputNames() {
  static const std::vector<std::string> names = {
      "trajectory.csv", "envelope.csv", "envelope_full.csv", "envelope_slow.csv", "comparison.csv",
      "summary.json",   "envelope.png", "comparison.png",    "order.csv",         "order.png",
      "raster.png",  // a network's (docs/networks.md)
      "fitted.yaml",    "fit.json",     "fit.png",           "measure.json",  // docs/fit.md
      "events.csv",     "envelope.svg", "envelope.pdf",      "comparison.svg",    "comparison.pdf",
  };
  return names;
}

void OutputDir::removeStaleOutputs() const {
  std::error_code ec;
  for (const auto& name : outputNames()) fs::remove(file(name), ec);
  // temporary files of earlier interrupted commands (".NAME.<pid>.part" whose process is gone)
  for (const auto& entry : fs::directory_iterator(path_, ec)) {
    const std::string n = entry.path().filename().string();
    if (isStalePrivateDirName(n)) {  // a plot's private folder (sim/record/private_dir.h)
      fs::remove_all(entry.path(), ec);
      continue;
    }
    if (n.size() < 7 || n[0] != '.' || n.compare(n.size() - 5, 5, ".part") != 0) continue;
    const std::string core = n.substr(1, n.size() - 6);  // NAME.<pid>
    const size_t dot = core.rfind('.');
    if (dot == std::string::npos) continue;
    const std::string name = core.substr(0, dot), pid_text = core.substr(dot + 1);
    bool ours = false;
    for (const auto& o : outputNames())  // NAME itself, or a helper file of it (NAME.dat)
      ours = ours || name == o || name.compare(0, o.size() + 1, o + ".") == 0;
    if (!ours || pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const long pid = std::stol(pid_text);
    if (pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
      fs::remove(entry.path(), ec);
  }
}

}  // namespace metrosync
