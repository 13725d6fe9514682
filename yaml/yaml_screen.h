// Screening of YAML text before any tree is built (issue 17): the text must be UTF-8 without
// control characters, one document, no aliases, a bounded number of nodes and a bounded depth, so
// that no input costs more than a small multiple of its size. Every problem has a location.
#pragma once

#include <optional>
#include <string>

namespace metrosync {

// A rig is a few maps per metronome: about 20 nodes each, 1000 metronomes (kMaxMetronomes,
// yaml/rig_limits.h) need 20000; the budget leaves room for comments-free verbose files while
// keeping the parsed tree (a few hundred bytes a node in yaml-cpp and in the loader) under ~25 MB.
constexpr int kMaxYamlNodes = 50000;
// The deepest rig key is metronomes.N.pendulum.mass: 5 levels; 16 allows any reasonable
// rewriting (flow style, a map where a value belongs) and stops "[[[[..." long before the
// parser's own recursion guard (2000) or the stack.
constexpr int kMaxYamlDepth = 16;
// The longest rig key has 16 characters; a longer key is a mistake, and quoting it whole in a
// message (or comparing it with every known key) must stay cheap.
constexpr std::size_t kMaxYamlKeyLength = 64;

struct YamlProblem {
  int line = 0, col = 0;  // 1-based; 0 = the text as a whole
  std::string what;
  bool syntax = false;  // a YAML syntax error (`what` is the parser's message)
};

// The first problem of `text`, or nullopt if it may be parsed.
std::optional<YamlProblem> screenYaml(const std::string& text);

}  // namespace metrosync
