// The --out directory of a command (SPEC section 3) and its default name.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace metrosync {

// `runs/<rig name>-<command>`, the rig name reduced to characters safe in a file name. With
// overrides (--set, in the order given) `-<hash>` is appended: 8 hex digits of overridesHash, so
// that runs of one rig with different overrides do not share (and overwrite) a folder; without
// them the name is exactly the SPEC's.
std::string defaultOutputDir(const std::string& rig_name, const std::string& command,
                             const std::vector<std::string>& overrides = {});
// FNV-1a (64 bits) of the overrides, each followed by a newline: the same on every machine.
std::uint64_t overridesHash(const std::vector<std::string>& overrides);

// The --out directory. The constructor creates it (with its parents): construct it only once the
// rig and the command line have been validated (SPEC 5: a bad rig writes nothing).
class OutputDir {
 public:
  explicit OutputDir(std::string path);  // throws std::runtime_error when it cannot
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Removes metrosync's own output files (the names below) left by an earlier command in this
  // directory, so that a stale trajectory.csv never sits next to a new summary.json. Other files
  // are left alone.
  void removeStaleOutputs() const;
  static const std::vector<std::string>& outputNames();

 private:
  std::string path_;
};

}  // namespace metrosync
