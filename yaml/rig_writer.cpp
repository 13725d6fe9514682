#include "yaml/rig_writer.h"

#include <cctype>
#include <charconv>
#include <sstream>

#include "yaml/rig_build.h"
#include "yaml/rig_loader.h"

namespace metrosync {

namespace {

// Plain when the scalar reads back as the same text (numbers, booleans, plain names); else in
// single quotes (a quote inside written twice).
std::string scalarText(const std::string& s) {
  if (parseRigNumber(s)) return s;
  bool plain = !s.empty();
  for (char ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.'))
      plain = false;
  for (const char* word : {"null", "Null", "NULL", "~"})
    if (s == word) plain = false;
  if (plain && !std::isdigit(static_cast<unsigned char>(s[0])) && s[0] != '-' && s[0] != '.')
    return s;
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("''") : std::string(1, ch);
  return q + "'";
}

void emit(std::ostringstream& os, const Node& n, int indent);

// `key: value` or `key:` and the nested block below it.
void emitEntry(std::ostringstream& os, const std::string& key, const Node& v, int indent) {
  os << std::string(indent, ' ') << key << ':';
  if (v.kind == Node::Kind::Scalar) {
    os << ' ' << scalarText(v.scalar) << '\n';
  } else if (v.kind == Node::Kind::Null) {
    os << '\n';
  } else if ((v.kind == Node::Kind::Map && v.map.empty()) ||
             (v.kind == Node::Kind::Seq && v.seq.empty())) {
    os << (v.kind == Node::Kind::Map ? " {}\n" : " []\n");
  } else {
    os << '\n';
    emit(os, v, indent + 2);
  }
}

void emit(std::ostringstream& os, const Node& n, int indent) {
  const std::string pad(indent, ' ');
  if (n.kind == Node::Kind::Map) {
    for (const Entry& e : n.map) emitEntry(os, e.key, e.value, indent);
  } else if (n.kind == Node::Kind::Seq) {
    for (const Node& item : n.seq) {
      if (item.kind == Node::Kind::Map && !item.map.empty()) {
        // "- first: ..." then the other keys aligned under it
        std::ostringstream inner;
        emit(inner, item, indent + 2);
        std::string text = inner.str();
        text.replace(indent, 2, "- ");
        os << text;
      } else if (item.kind == Node::Kind::Scalar) {
        os << pad << "- " << scalarText(item.scalar) << '\n';
      } else {
        os << pad << "-\n";
        emit(os, item, indent + 2);
      }
    }
  } else if (n.kind == Node::Kind::Scalar) {
    os << pad << scalarText(n.scalar) << '\n';
  }
}

}  // namespace

std::string rigYamlWithOverrides(const std::string& yaml_text, const std::string& display_name,
                                 const std::vector<std::string>& overrides,
                                 const std::vector<std::string>& header) {
  loadRigText(yaml_text, display_name, overrides);  // the rig must be valid
  const Node root = checkedRigTree(yaml_text, RigSource{display_name, overrides});
  std::ostringstream os;
  for (const std::string& line : header) os << "# " << line << '\n';
  emit(os, root, 0);
  return os.str();
}

std::string exactNumberText(double v) {
  char buf[40];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

}  // namespace metrosync
