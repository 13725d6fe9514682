#include "yaml/rig_tree.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <cstdio>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "yaml/utf8.h"

namespace metrosync {

const Node* Node::find(const std::string& key) const {
  for (const Entry& e : map)
    if (e.key == key) return &e.value;
  return nullptr;
}
Node* Node::find(const std::string& key) {
  for (Entry& e : map)
    if (e.key == key) return &e.value;
  return nullptr;
}

namespace {

// Line and column (1-based, in characters) of byte `offset` of `text`.
TreeError at(const std::string& text, std::size_t offset, int origin, std::string what) {
  TreeError e{Where{1, 1, origin}, std::move(what)};
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (b == '\n') {
      ++e.at.line;
      e.at.col = 1;
    } else if ((b & 0xC0) != 0x80) {  // not a continuation byte: a new character
      ++e.at.col;
    }
  }
  return e;
}

// UTF-8, and no control character but tab, line feed and carriage return (YAML 1.2, 5.1).
void screenCharacters(const std::string& text, int origin) {
  char buf[64];
  if (const auto bad = firstBadUtf8(text)) {
    std::snprintf(buf, sizeof buf, "not UTF-8 text (byte 0x%02X)",
                  static_cast<unsigned char>(text[*bad]));
    throw at(text, *bad, origin, buf);
  }
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (b == 0) throw at(text, i, origin, "a NUL byte: a rig is text");
    if ((b < 0x20 && b != '\t' && b != '\n' && b != '\r') || b == 0x7F) {
      std::snprintf(buf, sizeof buf, "control character 0x%02X: a rig is text", b);
      throw at(text, i, origin, buf);
    }
  }
}

// Builds the tree from the parser's events, counting nodes and depth as they come: an alias, a
// second document, too many nodes or too deep a nesting stop the parse where they are.
class TreeBuilder : public YAML::EventHandler {
 public:
  explicit TreeBuilder(int origin) : origin_(origin) {}
  // The tree, or the first bad key.
  Node take() {
    if (deferred_) throw *deferred_;
    return std::move(root_);
  }

  void OnDocumentStart(const YAML::Mark& m) override {
    if (++documents_ > 1)
      stop(m,
           "a second YAML document starts here: a rig is one document (remove the '---' or "
           "'...' line and what follows)");
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { add(leaf(m, Node::Kind::Null)); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override {
    stop(m, "an alias (*name): rigs do not support anchors and aliases, write the value out");
  }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    Node n = leaf(m, Node::Kind::Scalar);
    n.scalar = value;
    // the text was UTF-8, but an escape such as "\ud800" may not be
    if (firstBadUtf8(n.scalar))
      stop(m, "'" + printable(n.scalar.substr(0, 40)) + "' is not UTF-8 text after its escapes");
    add(std::move(n));
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    open(m, Node::Kind::Seq);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    open(m, Node::Kind::Map);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Open {
    Node node;
    bool have_key = false;  // a map: the key read, its value to come
    std::string key;
    Where key_at;
    // a map's keys so far and their lines: the duplicate check in constant time per key (a scan
    // of the map per key took > 20 s for 30 000 keys, issue 29)
    std::unordered_map<std::string, int> key_lines;
  };

  [[noreturn]] void stop(const YAML::Mark& m, const std::string& what) const {
    throw TreeError{where(m), what};
  }
  Where where(const YAML::Mark& m) const { return Where{m.line + 1, m.column + 1, origin_}; }

  Node leaf(const YAML::Mark& m, Node::Kind kind) {
    if (++nodes_ > kMaxYamlNodes)
      stop(m, "more than " + std::to_string(kMaxYamlNodes) +
                  " YAML nodes: too large for a rig (see docs/rig-limits.md)");
    Node n;
    n.kind = kind;
    n.at = where(m);
    return n;
  }

  void open(const YAML::Mark& m, Node::Kind kind) {
    if (static_cast<int>(stack_.size()) >= kMaxYamlDepth)
      stop(m, "nested more than " + std::to_string(kMaxYamlDepth) +
                  " levels deep (a rig needs 5, as in metronomes.0.pendulum.mass)");
    Open o;
    o.node = leaf(m, kind);
    stack_.push_back(std::move(o));
  }

  void close() {
    Node n = std::move(stack_.back().node);
    stack_.pop_back();
    add(std::move(n));
  }

  // A finished node into its parent: the root, a list item, a map's key or value.
  void add(Node n) {
    if (stack_.empty()) {
      root_ = std::move(n);
      return;
    }
    Open& p = stack_.back();
    if (p.node.kind == Node::Kind::Seq) {
      p.node.seq.push_back(std::move(n));
    } else if (!p.have_key) {
      addKey(p, n);
    } else {
      if (n.kind == Node::Kind::Null) n.at = p.key_at;  // no text of its own: point at its key
      p.node.map.push_back(Entry{std::move(p.key), p.key_at, std::move(n)});
      p.have_key = false;
    }
  }

  // A bad key is reported once the text has parsed: a syntax error further on (the parser
  // reports events before it finds one) is the better message.
  void addKey(Open& p, const Node& k) {
    if (k.kind != Node::Kind::Scalar) {
      defer(TreeError{k.at, "a key must be a plain name, not a map or list"});
    } else if (k.scalar.size() > kMaxYamlKeyLength) {
      defer(TreeError{k.at, "a key of " + std::to_string(k.scalar.size()) +
                                " characters (at most " + std::to_string(kMaxYamlKeyLength) +
                                "; no rig key is that long)"});
    } else if (const auto [it, fresh] = p.key_lines.emplace(k.scalar, k.at.line); !fresh) {
      defer(TreeError{k.at, "key '" + printable(k.scalar) +
                                "' appears twice in the same map (first at line " +
                                std::to_string(it->second) + ")"});
    }
    p.have_key = true;
    p.key = k.scalar;
    p.key_at = k.at;
  }

  void defer(TreeError e) {
    if (!deferred_) deferred_ = std::move(e);
  }

  int origin_;
  int documents_ = 0;
  std::optional<TreeError> deferred_;
  long nodes_ = 0;
  std::vector<Open> stack_;
  Node root_;
};

}  // namespace

namespace {

Node parseText(const std::string& text, int origin) {
  screenCharacters(text, origin);
  std::istringstream in(text);
  TreeBuilder builder(origin);
  try {
    YAML::Parser parser(in);
    while (parser.HandleNextDocument(builder)) {
    }
  } catch (const YAML::Exception& e) {
    const Where w =
        e.mark.is_null() ? Where{0, 0, origin} : Where{e.mark.line + 1, e.mark.column + 1, origin};
    throw TreeError{w, e.msg, true};
  }
  Node root = builder.take();
  if (root.kind == Node::Kind::Null) root.at = Where{1, 1, origin};
  return root;
}

}  // namespace

Node parseTree(const std::string& text, int origin) {
  // A sweep or a basin loads the same rig file's text once per point, its overrides applied to
  // the tree afterwards: the last file text parsed on this thread (origin 0; an override's value
  // has its own origin and is not kept) is kept with its tree, and a copy of the tree returned.
  // Parsing is ~1.3 M instructions for a two-metronome rig, the copy a few thousand.
  thread_local std::string last_text;
  thread_local Node last_tree;
  thread_local bool have_last = false;
  if (origin != 0) return parseText(text, origin);
  if (have_last && text == last_text) return last_tree;
  Node root = parseText(text, origin);
  last_text = text;
  last_tree = root;
  have_last = true;
  return root;
}

}  // namespace metrosync
