// Sensible ranges of a physical rig (issue 37, docs/sensible-ranges.md): the values real tabletop
// metronomes and boards have. A value outside its range is not an error of the model, which runs
// any rig the loader accepts, but most often a unit typed wrong: a pendulum of 22.5 mm written as
// `length: 22.5` (metres), a board of 143.2 g as `mass: 143.2` (kilograms), 14 degrees as
// `angle: 14` (radians). Each range spans the paper's measured value (section 3) by a factor of at
// least 20 on either side, and a factor of 1000 (g for kg, mm for m) or 57 (degrees for radians)
// from it falls outside. Scaled rigs are not checked: their numbers have no units to confuse.
#pragma once

#include <string>
#include <vector>

namespace metrosync {

// One key's range. `key` is relative to where it sits: the rig's top (`gravity`), a board
// (`mass` is platform.mass and platforms.N.mass) or a metronome (`pendulum.length` is
// metronomes.N.pendulum.length and platforms.N.metronomes.M.pendulum.length).
struct SensibleRange {
  enum class Scope { Top, Board, Metronome };
  Scope scope;
  const char* key;
  double lo, hi;      // inclusive, in the key's unit
  const char* unit;   // "m", "kg", "rad", ... ("" for a ratio)
  const char* paper;  // the paper's value (section 3), or the shipped rig's, as text
};
const std::vector<SensibleRange>& sensibleRanges();
// The full keys a range applies to (both forms for a board or a metronome), '*' for an index.
std::vector<std::string> sensibleRangeKeys(const SensibleRange& r);

// A value of a rig outside its range: the key as a path with indices
// (metronomes.0.pendulum.length) and the message, located as the loader's errors are:
//   rig.yaml:12:15: metronomes.0.pendulum.length = 22.5 m: outside 0.005 .. 0.5 m, the range of
//   real tabletop metronomes (in millimetres? the key is in metres; docs/sensible-ranges.md)
struct RangeFinding {
  std::string key;
  std::string message;
};

// Every value of the rig `yaml_text` after `overrides` that lies outside its range, in document
// order; none for a scaled rig. Throws RigError for a rig the loader would refuse.
std::vector<RangeFinding> sensibleRangeFindings(const std::string& yaml_text,
                                                const std::string& display_name,
                                                const std::vector<std::string>& overrides);

}  // namespace metrosync
