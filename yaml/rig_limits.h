// What a rig may ask for (issue 17, docs/rig-limits.md): the size of its file, the number of
// metronomes, the accuracy the integrators can honour, the output a run would write, a start that
// keeps every pendulum below the top. Each limit is checked when the rig is loaded (exit 2).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "models/rig.h"

namespace metrosync {

// A rig file is a few kB (n32.yaml, 32 metronomes, is 3 kB); 16 MiB bounds the read and what
// yaml-cpp holds while leaving room for any hand- or script-written rig.
constexpr std::uintmax_t kMaxRigFileBytes = 16u << 20;

// Every pendulum couples to every other through the platform: the engines' work per step grows as
// N^2 (dense mass matrix, N+1 coordinates) and a trajectory row holds 2N + 4 numbers. At 1000
// the mass matrix alone is 8 MB and a row ~40 kB, still runnable; the loader's tree stays below
// the YAML node budget (about 20 nodes a metronome, yaml/rig_tree.h).
constexpr std::size_t kMaxMetronomes = 1000;

// A name becomes an output folder (at most 255 bytes on common file systems) and a JSON string.
constexpr std::size_t kMaxNameBytes = 200;

// simulation.accuracy below this is refused: measured (docs/rig-limits.md), the direct engine's
// integrators finish the default rig at 1e-14 and fail with "step size underflow" below, and
// Simbody's stop taking steps near 1e-15; a relative local error target smaller than a few
// hundred double roundings (2.2e-16 each) cannot be met by any of them.
constexpr double kMinAccuracy = 1e-14;

// Trajectory rows print t with 12 significant digits (tools/report): below t_end * 1e-11 two
// consecutive sample times print the same. A factor 10 margin.
constexpr double kSampleResolution = 1e-10;

// Default output limit (bytes written by one run, all files): 2 GB; --max-output lifts it.
constexpr double kDefaultMaxOutputBytes = 2e9;

// The longest run any command integrates, in fast periods (2 pi time scales), whatever it writes:
// sweep and basin points, continue's settling run, fit's model runs and animate included.
// Measured (docs/rig-limits.md): the slow flow takes about 0.6 s per 10^6 periods, the full model
// of two metronomes about 1.2 s per 10^4; the paper's and shipped runs span at most ~10^5. At
// 10^8 a slow-flow run takes about a minute and the full model hours: still runnable, while
// tau = 1e300 or epsilon = 1e-12 (10^13 periods and more) is refused at once.
constexpr double kMaxRunPeriods = 1e8;

// A network of platforms (yaml/network_loader.h): at most this many platforms, and a stack (a
// platform `on` another, on another...) at most this deep. Each platform adds a coordinate and
// its own stick-slip events to every step, each level of a stack a chain of nested contacts:
// 1000 stacked platforms took 67 s for 0.01 s simulated (issue 29). The shipped networks have 2
// platforms, the Martens et al. geometry 2, a stack 2 levels.
constexpr std::size_t kMaxPlatforms = 64;
constexpr int kMaxStackDepth = 8;

// What a run of `rig` writes at most: the trajectory (every sample) and the envelope files (one
// row a fast period; compare's two envelopes and comparison.csv counted as four).
struct OutputEstimate {
  double sample_s = 0.0;  // the trajectory interval: simulation.sample or the engines' default
  double periods = 0.0;   // fast periods the run spans (kMaxRunPeriods)
  double trajectory_rows = 0.0;
  double envelope_rows = 0.0;
  double bytes = 0.0;
};
OutputEstimate estimateOutput(const Rig& rig);

// Why metronome `m` swings over the top from its start (the free pendulum's energy reaches that of
// the inverted position), or nullopt. Conservative only in the sense of the free pendulum: the
// escapement's steady amplitude is bounded by pi separately.
std::optional<std::string> overTheTop(const MetronomeSpec& m, double gravity);

}  // namespace metrosync
