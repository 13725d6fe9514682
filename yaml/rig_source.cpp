#include "yaml/rig_source.h"

#include <filesystem>

namespace metrosync::rigfile {

const char* kindName(const Node& n) {
  switch (n.kind) {
    case Node::Kind::Null:
      return "empty";
    case Node::Kind::Scalar:
      return "a single value";
    case Node::Kind::Map:
      return "a map";
    case Node::Kind::Seq:
      return "a list";
  }
  return "?";
}

std::string shown(const Node& n) {
  switch (n.kind) {
    case Node::Kind::Null:
      return "(nothing)";
    case Node::Kind::Scalar: {
      if (n.scalar.empty()) return "''";
      if (n.scalar.size() > 40) return printable(n.scalar.substr(0, 37)) + "...";
      return printable(n.scalar);
    }
    case Node::Kind::Map:
      return "(a map)";
    case Node::Kind::Seq:
      return "(a list)";
  }
  return "?";
}

std::string joinPath(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string stemOf(const std::string& display_name) {
  std::string stem = std::filesystem::path(display_name).stem().string();
  return stem.empty() ? std::string("rig") : stem;
}

}  // namespace metrosync::rigfile
