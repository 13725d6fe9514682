#include "sim/analysis/fit/start_guess.h"

#include <cmath>
#include <regex>
#include <stdexcept>

#include "sim/analysis/fit/section3.h"

namespace metrosync {

namespace {

const DataColumn* thetaOf(const MeasuredData& data, int i) {
  return data.find("theta_" + std::to_string(i + 1));
}

std::optional<StartGuess> decayGuess(const Rig& rig, const MeasuredData& data, int i,
                                     bool damping) {
  const DataColumn* c = thetaOf(data, i);
  if (!c) return std::nullopt;
  const FreeDecay d = measureFreeDecay(data.t_s, c->values);
  if (!(d.largest_amplitude < rig.metronomes[i].theta_c_rad) || !(d.rate_per_s.value > 0))
    return std::nullopt;
  const double v = damping ? dampingFromDecayRate(rig, i, d.rate_per_s).value : d.rate_per_s.value;
  return StartGuess{v, "free decay"};
}

std::optional<StartGuess> frictionGuess(const Rig& rig, const MeasuredData& data) {
  const DataColumn* c = data.find("x");
  if (!c || rig.numSwinging() > 0 || !(rig.platform.spring_N_m > 0)) return std::nullopt;
  const BoardDecay d = measureLinearDecay(data.t_s, c->values, rig.gravity_m_s2);
  if (!(d.mu_bar.value > 0)) return std::nullopt;
  return StartGuess{d.mu_bar.value, "linear decay"};
}

std::optional<StartGuess> steadyGuess(const Rig& rig, const MeasuredData& data, int i,
                                      bool impulse) {
  const DataColumn* c = thetaOf(data, i);
  if (!c) return std::nullopt;
  const SteadyAmplitude a = measureSteadyAmplitude(data.t_s, c->values);
  const MetronomeSpec& m = rig.metronomes[i];
  if (!(a.amplitude_rad.value >= std::sqrt(2.0) * m.theta_c_rad)) return std::nullopt;
  if (!impulse) return StartGuess{a.amplitude_rad.value, "steady amplitude"};
  const Impulse J = impulseFromSteadyAmplitude(rig, i, a.amplitude_rad, {m.damping_kg_s, 0.0});
  return StartGuess{J.impulse_Nms.value, "steady amplitude"};
}

}  // namespace

std::optional<StartGuess> section3Guess(const std::string& key, const Rig& rig,
                                        const MeasuredData& data) {
  static const std::regex pendulum(
      R"(^(?:platforms\.0\.)?metronomes\.(\d+)\.pendulum\.(damping|decay_rate)$)");
  static const std::regex escapement(
      R"(^(?:platforms\.0\.)?metronomes\.(\d+)\.escapement\.(impulse|steady_amplitude)$)");
  static const std::regex friction(R"(^(?:platform|platforms\.0)\.friction\.mu$)");
  std::smatch m;
  try {
    if (std::regex_match(key, m, pendulum)) {
      const int i = std::stoi(m[1]);
      if (i < static_cast<int>(rig.metronomes.size()))
        return decayGuess(rig, data, i, m[2] == "damping");
    } else if (std::regex_match(key, m, escapement)) {
      const int i = std::stoi(m[1]);
      if (i < static_cast<int>(rig.metronomes.size()))
        return steadyGuess(rig, data, i, m[2] == "impulse");
    } else if (std::regex_match(key, friction)) {
      return frictionGuess(rig, data);
    }
  } catch (const std::invalid_argument&) {
    // too few swings for the shortcut: the rig's value it is
  }
  return std::nullopt;
}

}  // namespace metrosync
