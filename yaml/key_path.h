// The key language of the command line (docs/keys.md): the one place where a rig key such as
// `metronomes.*.pendulum.damping` or `platforms.left.friction.mu` is parsed. `--set`, `--vary`,
// `--random`, `--param`, `--fold`, `--free` and the Python module's overrides all go through it
// (their keys resolved against the rig by resolveRigKey, yaml/rig_loader.h).
//
// A key is segments joined by '.': a segment of digits is a list index (from 0), `*` stands for
// every element of a list, and in the list `platforms` a platform's name may stand for its index.
// On a network of platforms `metronomes.*.REST` is every metronome of every platform.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace metrosync {

// A key that is not well formed, or does not fit the rig. what() says what is wrong, starting
// with the part of the key at fault ("platform..mu: empty key"); the caller says where the key
// came from (the option and what the user typed).
struct KeyError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The longest index a key may hold (8 digits): far above any list a rig can have (at most
// kMaxMetronomes metronomes, yaml/rig_limits.h), and a whole number in every integer type.
constexpr std::size_t kMaxKeyIndexDigits = 8;

class KeyPath {
 public:
  struct Segment {
    enum class Kind { Name, Index, Every };
    Kind kind = Kind::Name;
    std::string text;       // as typed: "pendulum", "0", "*", "left"
    std::size_t index = 0;  // Kind::Index
  };

  KeyPath() = default;
  // Parses `text` (spaces and tabs around it are dropped). Throws KeyError for an empty key or
  // segment, a '*' that is not a whole segment, or an '='.
  static KeyPath parse(const std::string& text);
  // The path of these segments (each already well formed).
  static KeyPath of(std::vector<Segment> segments);

  // The key as parsed, e.g. "metronomes.*.nu".
  const std::string& text() const { return text_; }
  const std::vector<Segment>& segments() const { return segments_; }
  std::size_t size() const { return segments_.size(); }
  const Segment& operator[](std::size_t i) const { return segments_[i]; }
  // The first `n` segments joined, as typed ("metronomes.*" for n = 2).
  std::string prefix(std::size_t n) const;
  // The last segment's text ("nu"), and the one before it ("" for a one-segment key).
  const std::string& leaf() const { return segments_.back().text; }
  std::string parent() const;
  // Does a segment stand for every element of a list?
  bool hasWildcard() const;
  // The key with every index written as '*' ("metronomes.*.pendulum.length" for
  // metronomes.0.pendulum.length): the form a table of keys is written in.
  std::string generic() const;

  bool operator==(const KeyPath& o) const { return text_ == o.text_; }
  bool operator!=(const KeyPath& o) const { return text_ != o.text_; }

 private:
  std::string text_;
  std::vector<Segment> segments_;
};

// "KEY=VALUE" split at the first '=': the key parsed, the value as written. Throws KeyError
// when there is no '=' or no key before it.
struct KeyAssignment {
  KeyPath key;
  std::string value;
};
KeyAssignment parseAssignment(const std::string& text);

// The key of "KEY=..." as written (before the first '='; the whole text without one), for the
// options whose value part has a syntax of its own (--vary, --random).
std::string keyTextOf(const std::string& assignment);

// A rig key that a path of `paths` and one of `others` both set (the same path, or one path
// inside the other: platform.friction and platform.friction.mu), or "" if there is none.
std::string sharedPath(const std::vector<KeyPath>& paths, const std::vector<KeyPath>& others);

// Internal to yaml/: the concrete paths (names and indices only) that `key` stands for in the rig
// tree `root` (yaml/rig_tree.h), in document order: each `*` becomes every index of its list, a
// platform's name its index, and on a network (a tree with `platforms`) `metronomes.*.REST`
// becomes platforms.P.metronomes.M.REST for every platform P and metronome M. A key whose path
// leaves the tree (a key the file does not write, such as a start absent from it) is kept as it
// is past that point. Throws KeyError: an index out of range, an unknown platform name, a `*`
// over a list the rig does not have (or that is empty).
struct Node;
std::vector<KeyPath> expandKey(const KeyPath& key, const Node& root);

// The name a single-platform rig's one platform answers to in `platforms.NAME...` (the name the
// network loader gives it, yaml/network_loader.h).
inline constexpr const char* kSinglePlatformName = "platform";

// Internal to yaml/: a key of a network's platform (`platforms.P.REST`) said on a single-platform
// rig (a tree without `platforms`), written in that rig's own keys: P is 0, `*` or `platform`
// (kSinglePlatformName), and platforms.P.mass / friction / spring become platform.REST,
// platforms.P.metronomes... metronomes..., platforms.P.start... start.... Any other key is
// returned as it is. Throws KeyError for another platform (naming the one the rig has) and for
// what a single rig's platform does not have (its name, `on`, the platform as one value).
KeyPath singlePlatformKey(const KeyPath& key, const Node& root);

}  // namespace metrosync
