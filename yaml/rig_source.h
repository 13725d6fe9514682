// Internal to yaml/: where a rig's messages point (the file's line and column, or the --set that
// wrote a node) and how values are shown in them.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "base/number_text.h"
#include "yaml/rig_error.h"
#include "yaml/rig_tree.h"
#include "yaml/utf8.h"

namespace metrosync::rigfile {

// "empty", "a single value", "a map", "a list"
const char* kindName(const Node& n);
// How a node is shown after "key = " in a message.
std::string shown(const Node& n);
// "path.key" ("key" at the top)
std::string joinPath(const std::string& path, const std::string& key);
// The rig's name from the file's: its stem ("rig" when it has none).
std::string stemOf(const std::string& display_name);

// Where messages point: the rig text (file:line:col) or the --set that wrote the node.
class Source {
 public:
  Source(std::string name, std::vector<std::string> overrides)
      : name_(std::move(name)), overrides_(std::move(overrides)) {}

  const std::string& name() const { return name_; }
  const std::vector<std::string>& overrides() const { return overrides_; }

  // "NAME:LINE:COL: what", or "NAME: --set K=V: what" for a node a --set wrote
  std::string message(const Where& at, const std::string& what) const {
    std::ostringstream os;
    os << printable(name_);
    if (at.origin > 0)
      os << ": --set " << printable(overrides_[at.origin - 1]);
    else if (at.line > 0)
      os << ':' << at.line << ':' << at.col;
    os << ": " << what;
    return os.str();
  }
  [[noreturn]] void fail(const Where& at, const std::string& what) const {
    throw RigError(message(at, what));
  }

 private:
  std::string name_;
  std::vector<std::string> overrides_;
};

}  // namespace metrosync::rigfile
