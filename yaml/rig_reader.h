// Internal to yaml/: reading a rig's values, each error naming the key, the value and where it
// was written.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "yaml/rig_source.h"

namespace metrosync::rigfile {

// A YAML scalar as a number (.inf, .nan and a leading + included); nullopt if it is not one.
std::optional<double> parseNumber(std::string s);

// A map being read: typed getters whose errors name the key, the value and where it was written.
class Reader {
 public:
  Reader(const Node& node, std::string path, const Source& src)
      : node_(&node), path_(std::move(path)), src_(&src) {}

  std::string path(const std::string& key) const { return joinPath(path_, key); }
  const std::string& path() const { return path_; }
  // The same node named `path` in messages (a network platform's keys in the single form).
  Reader withPath(std::string path) const { return Reader(*node_, std::move(path), *src_); }
  const Node* find(const std::string& key) const { return node_->find(key); }
  bool has(const std::string& key) const { return find(key) != nullptr; }
  const Where& at() const { return node_->at; }
  const Node& node() const { return *node_; }

  [[noreturn]] void missing(const std::string& key, const std::string& what) const {
    src_->fail(node_->at, path(key) + ": missing (" + what + ")");
  }
  [[noreturn]] void bad(const std::string& key, const std::string& why) const {
    const Node& n = *find(key);
    src_->fail(n.at, path(key) + " = " + shown(n) + ": " + why);
  }
  void forbid(const std::string& key, const std::string& why) const {
    if (has(key)) bad(key, why);
  }

  std::optional<double> optNumber(const std::string& key) const {
    const Node* n = find(key);
    if (!n) return std::nullopt;
    const std::optional<double> v = parseNumber(n->scalar);
    if (!v) bad(key, "must be a number");
    if (!std::isfinite(*v)) bad(key, "must be a finite number");
    return v;
  }
  double number(const std::string& key, const std::string& what) const {
    if (!has(key)) missing(key, what);
    return *optNumber(key);
  }
  std::optional<std::string> optText(const std::string& key) const {
    const Node* n = find(key);
    return n ? std::optional<std::string>(n->scalar) : std::nullopt;
  }
  std::string text(const std::string& key, const std::string& what) const {
    if (!has(key)) missing(key, what);
    return find(key)->scalar;
  }
  std::optional<bool> optBool(const std::string& key) const {
    const Node* n = find(key);
    if (!n) return std::nullopt;
    std::string low = n->scalar;
    for (char& ch : low) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (low == "true" || low == "yes" || low == "on") return true;
    if (low == "false" || low == "no" || low == "off") return false;
    bad(key, "must be true or false");
  }
  std::optional<Reader> optMap(const std::string& key) const {
    const Node* n = find(key);
    return n ? std::optional<Reader>(Reader(*n, path(key), *src_)) : std::nullopt;
  }
  Reader map(const std::string& key, const std::string& what) const {
    if (!has(key)) missing(key, what);
    return *optMap(key);
  }

 private:
  const Node* node_;
  std::string path_;
  const Source* src_;
};

// range checks: each returns the value, or fails naming key, value and rule
double positive(const Reader& r, const std::string& key, const std::string& what);
double nonNegative(const Reader& r, const std::string& key, double v);

// A name goes into files (summary.json, CSV headers) and, for the rig, an output folder.
std::optional<std::string> optName(const Reader& r);
// The rig's `name`, else `fallback`.
std::string readName(const Reader& top, const std::string& fallback);

}  // namespace metrosync::rigfile
