// Rigs for the event core's engine tests: two identical metronomes (the lost-tick rig of issue
// 10: nu 0.7, J 2.8, theta_c 0.9, A 1.9, epsilon 0.073) whose theta_c crossings are separated by
// delta in scaled time, in phase or in antiphase, started by phases or by theta/thetadot.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "base/constants.h"
#include "models/rig.h"
#include "yaml/rig_loader.h"

namespace metrosync::eventtests {

enum class Start { ByPhase, ByState };

inline std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// friction: the rig's platform.friction mapping; tau: the run's length in slow time.
inline Rig pairRig(Start start, bool antiphase, double delta, double tau,
                   const std::string& friction = "{law: coulomb, mu: 0.4}",
                   double accuracy = 1e-12) {
  const double A = 1.9;
  // the second metronome runs delta behind the first (theta ~ A sin(t + phi)), mirrored in
  // antiphase
  const double phi2 = (antiphase ? kPi : 0.0) - delta;
  std::string second;
  if (start == Start::ByPhase) {
    second = "{A: " + num(A) + ", phi: " + num(phi2) + "}";
  } else {
    const double s = antiphase ? -1.0 : 1.0;
    second = "{theta: " + num(s * A * std::sin(-delta)) +
             ", thetadot: " + num(s * A * std::cos(-delta)) + "}";
  }
  const std::string first =
      start == Start::ByPhase ? "{A: 1.9, phi: 0}" : "{theta: 0, thetadot: 1.9}";
  const std::string yaml =
      "units: scaled\nname: pair\nepsilon: 0.073\nplatform:\n  friction: " + friction +
      "\nmetronomes:\n"
      "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: " +
      first +
      "}\n"
      "  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: " +
      second + "}\nsimulation:\n  tau: " + num(tau) + "\n  accuracy: " + num(accuracy) + "\n";
  return loadRigText(yaml, "pair.yaml");
}

}  // namespace metrosync::eventtests
