#include "yaml/sensible_ranges.h"

#include "base/constants.h"
#include "base/number_text.h"
#include "models/rig.h"
#include "yaml/key_path.h"
#include "yaml/rig_build.h"
#include "yaml/rig_reader.h"
#include "yaml/rig_schema.h"

namespace metrosync {

using namespace rigfile;

// The sources of every number: docs/sensible-ranges.md (tests/yaml/test_sensible_ranges.cpp holds
// the page to this table).
const std::vector<SensibleRange>& sensibleRanges() {
  using S = SensibleRange::Scope;
  static const std::vector<SensibleRange> ranges = {
      {S::Top, "gravity", 9.7, 9.9, "m/s^2", "9.81"},
      {S::Board, "mass", 0.01, 20.0, "kg", "0.1432"},
      {S::Board, "friction.mu", 0.0, 1.0, "", "6.5e-4 to 4.6e-3"},
      {S::Board, "friction.mu_static", 0.0, 1.0, "", "(not measured)"},
      {S::Board, "spring.k", 0.01, 1.0e4, "N/m", "(not given)"},
      {S::Metronome, "box_mass", 0.001, 1.0, "kg", "0.0602"},
      {S::Metronome, "pendulum.mass", 0.001, 1.0, "kg", "0.0226"},
      {S::Metronome, "pendulum.length", 0.005, 0.5, "m", "0.0225"},
      {S::Metronome, "pendulum.inertia", 2.5e-8, 0.25, "kg m^2", "1.144e-5"},
      {S::Metronome, "pendulum.damping", 0.0, 1.0, "kg/s", "0.0226"},
      {S::Metronome, "pendulum.decay_rate", 0.0, 10.0, "1/s", "0.5"},
      {S::Metronome, "pendulum.air_drag", 0.0, 1.0e-4, "N m s^2", "(not measured)"},
      {S::Metronome, "escapement.angle", 0.0, 1.0, "rad", "0.244"},
      {S::Metronome, "escapement.impulse", 0.0, 0.01, "N m s", "1.49e-5"},
      {S::Metronome, "escapement.steady_amplitude", 0.05, 1.5, "rad", "0.785"},
      {S::Metronome, "start.angle", -1.5, 1.5, "rad", "0.785 and -0.785"},
  };
  return ranges;
}

std::vector<std::string> sensibleRangeKeys(const SensibleRange& r) {
  const std::string k = r.key;
  switch (r.scope) {
    case SensibleRange::Scope::Top:
      return {k};
    case SensibleRange::Scope::Board:
      return {"platform." + k, "platforms.*." + k};
    case SensibleRange::Scope::Metronome:
      return {"metronomes.*." + k, "platforms.*.metronomes.*." + k};
  }
  return {};
}

namespace {

const SensibleRange* rangeOf(const std::string& path) {
  const std::string generic = KeyPath::parse(path).generic();
  for (const SensibleRange& r : sensibleRanges())
    for (const std::string& k : sensibleRangeKeys(r))
      if (k == generic) return &r;
  return nullptr;
}

// The slip of units that brings `v` into the range, said as a question; empty when none does.
std::string unitHint(const SensibleRange& r, double v) {
  const std::string unit = r.unit;
  struct Slip {
    double factor;
    const char* typed;
    const char* meant;
  };
  std::vector<Slip> slips;
  if (unit == "m") slips = {{1e-3, "millimetres", "metres"}, {1e-2, "centimetres", "metres"}};
  if (unit == "kg") slips = {{1e-3, "grams", "kilograms"}};
  if (unit == "rad") slips = {{kPi / 180.0, "degrees", "radians"}};
  for (const Slip& s : slips)
    if (v * s.factor >= r.lo && v * s.factor <= r.hi)
      return std::string("in ") + s.typed + "? the key is in " + s.meant + "; ";
  return "";
}

std::string withUnit(const std::string& number, const SensibleRange& r) {
  return *r.unit ? number + " " + r.unit : number;
}

std::string rangeMessage(const SensibleRange& r, const std::string& path, const Node& n, double v) {
  const std::string what = r.scope == SensibleRange::Scope::Metronome ? "tabletop metronomes"
                           : r.scope == SensibleRange::Scope::Board   ? "tabletop boards"
                                                                      : "the Earth's surface";
  return path + " = " + withUnit(shown(n), r) + ": outside " + numberText(r.lo) + " .. " +
         withUnit(numberText(r.hi), r) + ", the range of " + what + " (" + unitHint(r, v) +
         "docs/sensible-ranges.md)";
}

void walk(const Node& n, const std::string& path, const Source& src,
          std::vector<RangeFinding>& out) {
  if (n.kind == Node::Kind::Map)
    for (const Entry& e : n.map) walk(e.value, joinPath(path, e.key), src, out);
  if (n.kind == Node::Kind::Seq)
    for (std::size_t i = 0; i < n.seq.size(); ++i)
      walk(n.seq[i], joinPath(path, std::to_string(i)), src, out);
  if (n.kind != Node::Kind::Scalar) return;
  const SensibleRange* r = rangeOf(path);
  const std::optional<double> v = r ? parseNumber(n.scalar) : std::nullopt;
  if (v && !(*v >= r->lo && *v <= r->hi))
    out.push_back({path, src.message(n.at, rangeMessage(*r, path, n, *v))});
}

}  // namespace

std::vector<RangeFinding> sensibleRangeFindings(const std::string& yaml_text,
                                                const std::string& display_name,
                                                const std::vector<std::string>& overrides) {
  const Node root = checkedRigTree(yaml_text, RigSource{display_name, overrides});
  std::vector<RangeFinding> out;
  if (unitsOf(root) != Units::Physical) return out;
  walk(root, "", Source(display_name, overrides), out);
  return out;
}

}  // namespace metrosync
