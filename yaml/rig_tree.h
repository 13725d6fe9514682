// The rig as a tree that remembers where each node was written, built in one pass over the YAML
// parser's events (issue 17): the text must be UTF-8 without control characters, one document,
// no aliases, a bounded number of nodes and a bounded depth, so that no input costs more than a
// small multiple of its size. Internal to yaml/; no yaml-cpp type crosses it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace metrosync {

// A rig is a few maps per metronome: about 20 nodes each, 1000 metronomes (kMaxMetronomes,
// yaml/rig_limits.h) need 20000; the budget leaves room for verbose files while keeping the tree
// (a few hundred bytes a node) under ~25 MB.
constexpr int kMaxYamlNodes = 50000;
// The deepest rig key is metronomes.N.pendulum.mass: 5 levels; 16 allows any reasonable
// rewriting (flow style, a map where a value belongs) and stops "[[[[..." long before the
// parser's own recursion guard (2000, "bad file") or the stack.
constexpr int kMaxYamlDepth = 16;
// The longest rig key has 16 characters; a longer key is a mistake, and quoting it whole in a
// message (or comparing it with every known key) must stay cheap.
constexpr std::size_t kMaxYamlKeyLength = 64;

struct Where {
  int line = 0, col = 0;  // 1-based; 0 = unknown
  int origin = 0;         // 0: the rig text; k > 0: the k-th --set
};

struct Entry;
struct Node {
  enum class Kind { Null, Scalar, Map, Seq };
  Kind kind = Kind::Null;
  std::string scalar;
  std::vector<Entry> map;  // in document order
  std::vector<Node> seq;
  Where at;

  const Node* find(const std::string& key) const;
  Node* find(const std::string& key);
};
struct Entry {
  std::string key;
  Where key_at;
  Node value;
};

// What is wrong with a text, and where (in the text; line 0 when the whole text is meant).
struct TreeError {
  Where at;
  std::string what;
  bool syntax = false;  // a YAML syntax error: `what` is the parser's message
};

// The tree of `text` (a Null node at 1:1 for an empty text); every node's Where has `origin`.
// Throws TreeError. Duplicate keys are errors (YAML forbids them; yaml-cpp keeps both).
Node parseTree(const std::string& text, int origin);

}  // namespace metrosync
