// The built-in default rig (SPEC section 2, the paper's experiment).
#include "yaml/rig_loader.h"

namespace metrosync {

std::string defaultRigYaml() {
  // keep byte for byte equal to yaml/rigs/experiment.yaml (tests/yaml checks it)
  return R"(# The paper's experiment (section 3): two Wittner Super-Mini Ruby metronomes, adjustable weight
# removed, on a platform on large PVC rollers on a smooth table (the lowest friction measured),
# started near antiphase. The built-in default rig of `metrosync run` and `metrosync compare`.
units: physical
name: experiment
gravity: 9.81
platform:
  mass: 0.1432                  # kg, the board alone: M = 0.3088 kg with both metronomes
  friction: {law: coulomb, mu: 6.5e-4}
metronomes:
  - name: A
    box_mass: 0.0602            # kg, 82.8 g with its pendulum
    pendulum:
      mass: 0.0226              # kg; inertia defaults to mass * length^2
      length: 0.0225            # m, pivot to the fixed weight
      decay_rate: 0.5           # 1/s, measured below the escapement angle on a still table
    escapement:
      angle: 0.244              # rad (14 deg)
      steady_amplitude: 0.785   # rad (45 deg), alone on a still table
    start: {angle: 0.785, rate: 0.0}
  - name: B
    box_mass: 0.0602
    pendulum:
      mass: 0.0226
      length: 0.0225
      decay_rate: 0.5
    escapement:
      angle: 0.244
      steady_amplitude: 0.785
    start: {angle: -0.785, rate: 0.25}
simulation:
  duration: 200                 # s
)";
}

Rig defaultRig(const std::vector<std::string>& overrides, const LoadOptions& options) {
  return loadRigText(defaultRigYaml(), "<default rig>", overrides, options);
}

}  // namespace metrosync
