#include "yaml/rig_limits.h"

#include <cmath>

#include "base/constants.h"
#include "base/number_text.h"
#include "models/scaling.h"

namespace metrosync {

namespace {

// The engines' default trajectory interval (direct and Simbody engines: period / 20), and the
// envelope's one row per fast period (sim/record/envelope_recorder.h; the slow flow's rows are
// on the same grid).
constexpr double kDefaultSamplesPerPeriod = 20.0;
constexpr double kEnvelopeRowsPerPeriod = 1.0;
// compare writes two envelopes and comparison.csv (tau, A_i and psi_j of both models: about two
// envelopes wide): at most four envelopes' worth.
constexpr double kEnvelopeFiles = 4.0;
// Widest number printed: %.12g (trajectory) as "-1.23456789012e-308" (19) plus a separator;
// %.10g (envelope) 17 plus a separator.
constexpr double kTrajectoryBytesPerNumber = 20.0;
constexpr double kEnvelopeBytesPerNumber = 18.0;

}  // namespace

OutputEstimate estimateOutput(const Rig& rig) {
  const double n = static_cast<double>(rig.metronomes.size());
  const double period = kTwoPi * computeScaled(rig).time_scale_s;
  OutputEstimate e;
  e.sample_s = rig.sim.sample_s > 0 ? rig.sim.sample_s : period / kDefaultSamplesPerPeriod;
  e.trajectory_rows = std::floor(rig.sim.t_end_s / e.sample_s) + 1.0;
  e.periods = rig.sim.t_end_s / period;
  e.envelope_rows = std::floor(e.periods * kEnvelopeRowsPerPeriod) + 1.0;
  // trajectory: t, x, xdot, (theta_i, thetadot_i), platform; envelope: tau, A_i, psi_j, r
  e.bytes = e.trajectory_rows * (2.0 * n + 4.0) * kTrajectoryBytesPerNumber +
            kEnvelopeFiles * e.envelope_rows * (2.0 * n + 1.0) * kEnvelopeBytesPerNumber;
  return e;
}

std::optional<std::string> overTheTop(const MetronomeSpec& m, double gravity) {
  if (m.locked) return std::nullopt;
  // energy of the free pendulum about its pivot, zero at rest hanging down; the top is at
  // theta = pi, energy 2 m g L
  const double mgl = m.pendulum_mass_kg * gravity * m.length_m;
  const double energy = 0.5 * m.inertia_kgm2 * m.start_rate_rad_s * m.start_rate_rad_s +
                        mgl * (1.0 - std::cos(m.start_angle_rad));
  const bool beyond = std::fabs(m.start_angle_rad) >= kPi;
  if (!beyond && energy < 2.0 * mgl) return std::nullopt;
  const std::string start = "the start (angle " + numberText(m.start_angle_rad) + " rad, rate " +
                            numberText(m.start_rate_rad_s) +
                            " rad/s) sends the pendulum over the top: ";
  if (beyond) return start + "|angle| must be < pi";
  return start + "its energy 1/2 I rate^2 + m g L (1 - cos angle) = " + numberText(energy) +
         " J reaches 2 m g L = " + numberText(2.0 * mgl) +
         " J (the free pendulum's amplitude would be pi); start it lower or slower";
}

}  // namespace metrosync
