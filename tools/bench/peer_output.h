// The careful peer's answer (../shared/peer/README.md): one JSON line on stdout with the final
// state, the timing medians of its --repeat integrations and its counts. Read into values here;
// what they mean for the bench (the scaled final state, the counts) is tools/bench/peer_scene.h.
#pragma once

#include <string>
#include <vector>

namespace metrosync::bench {

struct PeerOutput {
  int n = 0;  // metronomes
  std::string method;
  double rtol = 0.0, atol = 0.0;
  double t = 0.0;                      // scaled time of the final state
  std::vector<double> state;           // th_1..th_N, th'_1..th'_N, x, x' (scaled), 2N + 2 values
  std::string mode;                    // the platform at the end: stick, slip+, slip-, free
  double wall_ms = 0.0, cpu_ms = 0.0;  // medians over the repeats, integration only
  std::vector<double> wall_ms_runs;    // every repeat's wall time
  long steps = 0, rhs_calls = 0, events = 0, restarts = 0;
  std::vector<long> kicks;  // ticks per metronome
  long platform_events = 0, stick_to_slip = 0, slip_stops = 0;
  double stick_time = 0.0;
};

// The last non-empty line of `text` (the peer's stdout) as a PeerOutput. Throws
// std::invalid_argument naming what is wrong: not JSON, a key missing or of the wrong type, a
// state that is not 2N + 2 numbers, kicks that are not N.
PeerOutput parsePeerOutput(const std::string& text);

}  // namespace metrosync::bench
