#include "yaml/units_advice.h"

#include <vector>

#include "yaml/key_path.h"

namespace metrosync::rigfile {

namespace {

struct Advice {
  Units rig;           // the rig's units (the key is the other units')
  const char* parent;  // generic: indices as '*'
  const char* key;
  const char* text;  // "{P}" stands for the parent as typed
};

// The scaled parameters are functions of the physical ones (models/scaling.h): each scaled key
// points to the physical keys that set it, and back.
const std::vector<Advice>& advice() {
  static const std::vector<Advice> table = {
      {Units::Physical, "", "epsilon",
       "epsilon follows from the masses: set platform.mass (kg); `metrosync scale` prints it"},
      {Units::Physical, "metronomes.*", "nu",
       "set {P}.pendulum.damping (kg/s) or {P}.pendulum.decay_rate (1/s)"},
      {Units::Physical, "metronomes.*", "J",
       "set {P}.escapement.impulse (N m s) or {P}.escapement.steady_amplitude (rad)"},
      {Units::Physical, "metronomes.*", "theta_c", "set {P}.escapement.angle (rad)"},
      {Units::Physical, "metronomes.*", "alpha",
       "the detuning follows from the pendulum: set {P}.pendulum.length (m) or "
       "{P}.pendulum.inertia (kg m^2)"},
      {Units::Physical, "metronomes.*", "zeta",
       "the coupling follows from the pendulum: set {P}.pendulum.mass (kg) and "
       "{P}.pendulum.length (m)"},
      {Units::Physical, "metronomes.*.start", "A", "set {P}.angle (rad) and {P}.rate (rad/s)"},
      {Units::Physical, "metronomes.*.start", "phi", "set {P}.angle (rad) and {P}.rate (rad/s)"},
      {Units::Physical, "metronomes.*.start", "theta", "set {P}.angle (rad)"},
      {Units::Physical, "metronomes.*.start", "thetadot", "set {P}.rate (rad/s)"},
      {Units::Physical, "simulation", "tau", "set {P}.duration (s)"},
      {Units::Scaled, "", "gravity", "a scaled rig has g = 1: leave gravity out"},
      {Units::Scaled, "platform", "mass", "the board's mass is in epsilon: set epsilon"},
      {Units::Scaled, "platform", "spring", "a board on springs is a physical rig"},
      {Units::Scaled, "", "platforms", "a network of platforms is a physical rig"},
      {Units::Scaled, "", "couplings", "a network of platforms is a physical rig"},
      {Units::Scaled, "metronomes.*", "box_mass", "the masses are in epsilon and {P}.zeta"},
      {Units::Scaled, "metronomes.*", "pendulum", "set {P}.nu, {P}.alpha and {P}.zeta"},
      {Units::Scaled, "metronomes.*", "escapement", "set {P}.J and {P}.theta_c"},
      {Units::Scaled, "metronomes.*", "locked", "a locked metronome is a physical rig's"},
      {Units::Scaled, "metronomes.*.start", "angle",
       "set {P}.theta (or {P}.A and {P}.phi), in scaled units"},
      {Units::Scaled, "metronomes.*.start", "rate",
       "set {P}.thetadot (or {P}.A and {P}.phi), in scaled units"},
      {Units::Scaled, "simulation", "duration", "set {P}.tau (slow time)"},
  };
  return table;
}

std::string generic(const std::string& parent) {
  try {
    return parent.empty() ? "" : KeyPath::parse(parent).generic();
  } catch (const KeyError&) {
    return parent;
  }
}

}  // namespace

std::string otherUnitsAdvice(const std::string& parent, const std::string& key, Units rig_units) {
  const std::string g = generic(parent);
  for (const Advice& a : advice()) {
    if (a.rig != rig_units || g != a.parent || key != a.key) continue;
    std::string text = a.text;
    for (std::size_t at = text.find("{P}"); at != std::string::npos; at = text.find("{P}"))
      text.replace(at, 3, parent);
    return std::string("this rig is ") + (rig_units == Units::Physical ? "physical" : "scaled") +
           ": " + text;
  }
  return "";
}

}  // namespace metrosync::rigfile
