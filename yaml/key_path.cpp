#include "yaml/key_path.h"

#include <algorithm>
#include <cctype>
#include <utility>

#include "yaml/rig_tree.h"
#include "yaml/utf8.h"

namespace metrosync {

namespace {

std::string trimmed(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

bool allDigits(const std::string& s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

KeyPath::Segment segmentOf(const std::string& text, const std::string& key_so_far) {
  KeyPath::Segment s;
  s.text = text;
  if (text.empty()) throw KeyError("'" + printable(key_so_far) + "': empty key");
  if (text == "*") {
    s.kind = KeyPath::Segment::Kind::Every;
  } else if (text.find('*') != std::string::npos) {
    throw KeyError(printable(key_so_far) + ": '*' stands alone between dots (metronomes.*.nu)");
  } else if (allDigits(text)) {
    if (text.size() > kMaxKeyIndexDigits)
      throw KeyError(printable(key_so_far) + ": an index of more than " +
                     std::to_string(kMaxKeyIndexDigits) + " digits");
    s.kind = KeyPath::Segment::Kind::Index;
    s.index = std::stoul(text);
  }
  return s;
}

// The segment of list index i, written as an index.
KeyPath::Segment indexSegment(std::size_t i) {
  KeyPath::Segment s;
  s.kind = KeyPath::Segment::Kind::Index;
  s.text = std::to_string(i);
  s.index = i;
  return s;
}

std::string joined(const std::vector<KeyPath::Segment>& segs) {
  std::string out;
  for (const KeyPath::Segment& s : segs) out += (out.empty() ? "" : ".") + s.text;
  return out;
}

}  // namespace

KeyPath KeyPath::parse(const std::string& text) {
  KeyPath k;
  k.text_ = trimmed(text);
  if (k.text_.empty()) throw KeyError("no key (a key is a path such as platform.friction.mu)");
  if (k.text_.find('=') != std::string::npos)
    throw KeyError(printable(k.text_) + ": a key has no '=' (this option takes a key alone)");
  std::size_t from = 0;
  for (;;) {
    const std::size_t dot = k.text_.find('.', from);
    const std::size_t end = dot == std::string::npos ? k.text_.size() : dot;
    k.segments_.push_back(segmentOf(k.text_.substr(from, end - from), k.text_.substr(0, end)));
    if (dot == std::string::npos) break;
    from = dot + 1;
  }
  return k;
}

KeyPath KeyPath::of(std::vector<Segment> segments) {
  KeyPath k;
  k.text_ = joined(segments);
  k.segments_ = std::move(segments);
  return k;
}

std::string KeyPath::prefix(std::size_t n) const {
  return joined({segments_.begin(), segments_.begin() + std::min(n, segments_.size())});
}

std::string KeyPath::parent() const {
  return segments_.size() < 2 ? std::string() : segments_[segments_.size() - 2].text;
}

bool KeyPath::hasWildcard() const {
  return std::any_of(segments_.begin(), segments_.end(),
                     [](const Segment& s) { return s.kind == Segment::Kind::Every; });
}

std::string KeyPath::generic() const {
  std::string g;
  for (const Segment& s : segments_)
    g += (g.empty() ? "" : ".") + (s.kind == Segment::Kind::Name ? s.text : std::string("*"));
  return g;
}

KeyAssignment parseAssignment(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || trimmed(text.substr(0, eq)).empty())
    throw KeyError("expected KEY=VALUE (e.g. platform.friction.mu=0.3)");
  return KeyAssignment{KeyPath::parse(text.substr(0, eq)), text.substr(eq + 1)};
}

std::string keyTextOf(const std::string& assignment) {
  return assignment.substr(0, assignment.find('='));
}

std::string sharedPath(const std::vector<KeyPath>& paths, const std::vector<KeyPath>& others) {
  // `a` is `b` or holds it (a map or list above it)
  const auto within = [](const std::string& a, const std::string& b) {
    return b.compare(0, a.size(), a) == 0 && (b.size() == a.size() || b[a.size()] == '.');
  };
  for (const KeyPath& p : paths)
    for (const KeyPath& q : others)
      if (within(p.text(), q.text()) || within(q.text(), p.text()))
        return p.size() > q.size() ? p.text() : q.text();
  return "";
}

namespace {

// Walks `key` from segment i at `node` (nullptr: past the rig's tree), the concrete segments
// so far in `done`, the results into `out`.
class Expander {
 public:
  Expander(const KeyPath& key, std::vector<KeyPath>& out) : key_(key), out_(out) {}

  void walk(std::size_t i, const Node* node, std::vector<KeyPath::Segment>& done) {
    if (i == key_.size()) {
      out_.push_back(KeyPath::of(done));
      return;
    }
    const KeyPath::Segment& seg = key_[i];
    if (node && node->kind == Node::Kind::Seq) return element(i, *node, done);
    if (seg.kind != KeyPath::Segment::Kind::Name) {
      // an index or '*' where the rig has no list (the schema wants one: the rig has none yet)
      const std::string at = joined(done);
      if (!node || node->kind == Node::Kind::Null)
        throw KeyError(here(done, seg) + ": " + at + " has no entries" +
                       (seg.kind == KeyPath::Segment::Kind::Every
                            ? " for '*' to stand for"
                            : " (index " + seg.text + " is out of range)"));
      throw KeyError(here(done, seg) + ": " + at + " is not a list in the rig");
    }
    const Node* next = node && node->kind == Node::Kind::Map ? node->find(seg.text) : nullptr;
    done.push_back(seg);
    walk(i + 1, next, done);
    done.pop_back();
  }

 private:
  static std::string here(const std::vector<KeyPath::Segment>& done, const KeyPath::Segment& s) {
    return printable(joined(done) + (done.empty() ? "" : ".") + s.text);
  }

  // Segment i of a list: an index, '*' (every element), or an element's name.
  void element(std::size_t i, const Node& list, std::vector<KeyPath::Segment>& done) {
    const KeyPath::Segment& seg = key_[i];
    const std::string at = joined(done);
    std::vector<std::size_t> picked;
    if (seg.kind == KeyPath::Segment::Kind::Every) {
      if (list.seq.empty())
        throw KeyError(here(done, seg) + ": " + at + " has no entries for '*' to stand for");
      for (std::size_t k = 0; k < list.seq.size(); ++k) picked.push_back(k);
    } else if (seg.kind == KeyPath::Segment::Kind::Index) {
      if (seg.index >= list.seq.size())
        throw KeyError(here(done, seg) + ": index " + seg.text + " is out of range (" + at +
                       " has " + std::to_string(list.seq.size()) + " entries, indices from 0)");
      picked.push_back(seg.index);
    } else {
      picked.push_back(named(list, seg, done));
    }
    for (std::size_t k : picked) {
      done.push_back(indexSegment(k));
      walk(i + 1, &list.seq[k], done);
      done.pop_back();
    }
  }

  // The index of the element of `list` whose `name` is the segment's text.
  std::size_t named(const Node& list, const KeyPath::Segment& seg,
                    const std::vector<KeyPath::Segment>& done) {
    std::vector<std::size_t> hits;
    std::string names;
    for (std::size_t k = 0; k < list.seq.size(); ++k) {
      const Node* n = list.seq[k].kind == Node::Kind::Map ? list.seq[k].find("name") : nullptr;
      if (!n || n->kind != Node::Kind::Scalar) continue;
      names += (names.empty() ? "" : ", ") + printable(n->scalar);
      if (n->scalar == seg.text) hits.push_back(k);
    }
    const std::string at = joined(done);
    if (hits.empty())
      throw KeyError(here(done, seg) + ": no entry of " + at + " is named '" + printable(seg.text) +
                     "'" + (names.empty() ? " (they have no names)" : " (names: " + names + ")"));
    if (hits.size() > 1)
      throw KeyError(here(done, seg) + ": " + at + "." + std::to_string(hits[0]) + " and " + at +
                     "." + std::to_string(hits[1]) + " are both named '" + printable(seg.text) +
                     "'");
    return hits[0];
  }

  const KeyPath& key_;
  std::vector<KeyPath>& out_;
};

// A network's `metronomes.*.REST`: every metronome of every platform (docs/keys.md).
void expandNetworkMetronomes(const KeyPath& key, const Node& platforms, Expander& e) {
  if (key.size() < 2 || key[1].kind != KeyPath::Segment::Kind::Every)
    throw KeyError(printable(key.prefix(2)) +
                   ": a network's metronomes are under its platforms: write "
                   "platforms.NAME.metronomes.N... for one of them, or metronomes.*... for "
                   "every metronome of every platform");
  std::vector<KeyPath::Segment> done;
  for (std::size_t p = 0; p < platforms.seq.size(); ++p) {
    const Node* list = platforms.seq[p].find("metronomes");
    if (!list || list->kind != Node::Kind::Seq) continue;
    done = {KeyPath::Segment{KeyPath::Segment::Kind::Name, "platforms", 0}, indexSegment(p),
            KeyPath::Segment{KeyPath::Segment::Kind::Name, "metronomes", 0}};
    e.walk(1, list, done);
  }
}

}  // namespace

std::vector<KeyPath> expandKey(const KeyPath& key, const Node& root) {
  std::vector<KeyPath> out;
  Expander e(key, out);
  const Node* platforms = root.kind == Node::Kind::Map ? root.find("platforms") : nullptr;
  if (platforms && platforms->kind == Node::Kind::Seq && key[0].text == "metronomes") {
    expandNetworkMetronomes(key, *platforms, e);
    if (out.empty())
      throw KeyError(printable(key.prefix(2)) +
                     ": the network has no metronomes for '*' to "
                     "stand for");
    return out;
  }
  std::vector<KeyPath::Segment> done;
  e.walk(0, &root, done);
  return out;
}

namespace {

// Segment 1 of platforms.P... on a single-platform rig: its one platform, or a KeyError.
void checkSinglePlatform(const KeyPath& key) {
  const KeyPath::Segment& p = key[1];
  const std::string at = printable(key.prefix(2));
  if (p.kind == KeyPath::Segment::Kind::Index && p.index != 0)
    throw KeyError(
        at + ": index " + p.text +
        " is out of range (a single-platform rig has one platform, platforms.0, named '" +
        kSinglePlatformName + "')");
  if (p.kind == KeyPath::Segment::Kind::Name && p.text != kSinglePlatformName)
    throw KeyError(at + ": no entry of platforms is named '" + printable(p.text) +
                   "' (names: " + kSinglePlatformName + "; this rig has one platform)");
  if (key.size() == 2)
    throw KeyError(at + ": a single-platform rig's platform is set key by key (" + at +
                   ".friction, " + at + ".metronomes, ...), not as one value");
}

}  // namespace

KeyPath singlePlatformKey(const KeyPath& key, const Node& root) {
  if (root.kind != Node::Kind::Map || root.find("platforms") || key.size() < 2 ||
      key[0].kind != KeyPath::Segment::Kind::Name || key[0].text != "platforms")
    return key;
  checkSinglePlatform(key);
  const std::string& what = key[2].text;
  std::vector<KeyPath::Segment> out(key.segments().begin() + 2, key.segments().end());
  if (what == "name" || what == "on")
    throw KeyError(printable(key.prefix(3)) + ": a single-platform rig's platform " +
                   (what == "name" ? std::string("is named '") + kSinglePlatformName + "'"
                                   : std::string("rests on the table")) +
                   " (give the rig platforms: [...] for a network, docs/networks.md)");
  if (what != "metronomes" && what != "start")
    out.insert(out.begin(), KeyPath::Segment{KeyPath::Segment::Kind::Name, "platform", 0});
  return KeyPath::of(std::move(out));
}

}  // namespace metrosync
