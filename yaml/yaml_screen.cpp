#include "yaml/yaml_screen.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <cstdio>
#include <sstream>
#include <vector>

#include "yaml/utf8.h"

namespace metrosync {

namespace {

// Line and column (1-based, in characters) of byte `offset` of `text`.
YamlProblem at(const std::string& text, std::size_t offset, std::string what) {
  YamlProblem p{1, 1, std::move(what)};
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (b == '\n') {
      ++p.line;
      p.col = 1;
    } else if ((b & 0xC0) != 0x80) {  // not a continuation byte: a new character
      ++p.col;
    }
  }
  return p;
}

// UTF-8, and no control character but tab, line feed and carriage return (YAML 1.2, 5.1).
std::optional<YamlProblem> screenCharacters(const std::string& text) {
  if (const auto bad = firstBadUtf8(text)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "not UTF-8 text (byte 0x%02X)",
                  static_cast<unsigned char>(text[*bad]));
    return at(text, *bad, buf);
  }
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (b == 0) return at(text, i, "a NUL byte: a rig is text");
    if ((b < 0x20 && b != '\t' && b != '\n' && b != '\r') || b == 0x7F) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "control character 0x%02X: a rig is text", b);
      return at(text, i, buf);
    }
  }
  return std::nullopt;
}

struct Stop {
  YamlProblem problem;
};

// Counts nodes and depth as the parser reports them; refuses aliases, a second document and
// over-long keys by throwing Stop.
class Screen : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& m) override {
    if (++documents_ > 1)
      stop(m,
           "a second YAML document starts here: a rig is one document (remove the '---' or "
           "'...' line and what follows)");
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { node(m, nullptr); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override {
    stop(m, "an alias (*name): rigs do not support anchors and aliases, write the value out");
  }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    node(m, &value);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    open(m, false);
  }
  void OnSequenceEnd() override { stack_.pop_back(); }
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    open(m, true);
  }
  void OnMapEnd() override { stack_.pop_back(); }

 private:
  struct Level {
    bool map = false;
    long items = 0;  // in a map: keys and values alternate, keys at even counts
  };

  [[noreturn]] static void stop(const YAML::Mark& m, const std::string& what) {
    throw Stop{YamlProblem{m.line + 1, m.column + 1, what}};
  }

  void node(const YAML::Mark& m, const std::string* scalar) {
    if (++nodes_ > kMaxYamlNodes)
      stop(m, "more than " + std::to_string(kMaxYamlNodes) +
                  " YAML nodes: too large for a rig (see docs/rig-limits.md)");
    if (!stack_.empty() && stack_.back().map && stack_.back().items % 2 == 0 && scalar &&
        scalar->size() > kMaxYamlKeyLength)
      stop(m, "a key of " + std::to_string(scalar->size()) + " characters (at most " +
                  std::to_string(kMaxYamlKeyLength) + "; no rig key is that long)");
    if (!stack_.empty()) ++stack_.back().items;
  }

  void open(const YAML::Mark& m, bool map) {
    node(m, nullptr);
    if (static_cast<int>(stack_.size()) >= kMaxYamlDepth)
      stop(m, "nested more than " + std::to_string(kMaxYamlDepth) +
                  " levels deep (a rig needs 5, as in metronomes.0.pendulum.mass)");
    stack_.push_back(Level{map, 0});
  }

  int documents_ = 0;
  long nodes_ = 0;
  std::vector<Level> stack_;
};

}  // namespace

std::optional<YamlProblem> screenYaml(const std::string& text) {
  if (auto p = screenCharacters(text)) return p;
  std::istringstream in(text);
  try {
    YAML::Parser parser(in);
    Screen screen;
    while (parser.HandleNextDocument(screen)) {
    }
  } catch (const Stop& s) {
    return s.problem;
  } catch (const YAML::Exception& e) {
    if (e.mark.is_null()) return YamlProblem{0, 0, e.msg, true};
    return YamlProblem{e.mark.line + 1, e.mark.column + 1, e.msg, true};
  }
  return std::nullopt;
}

}  // namespace metrosync
