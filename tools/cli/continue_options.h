// The options of `metrosync continue` and its rig (both models: tools/cli/continue.h runs the
// slow flow's continuation, tools/cli/continue_full.h the full model's).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "models/rig.h"

namespace metrosync::cli {

struct ContinueOptions {
  std::string rig_path;           // empty: the built-in default rig
  std::string model = "slow";     // --model slow|full (full: tools/cli/continue_full.h)
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
  std::string param;              // --param KEY
  double to = 0.0;                // --to VALUE
  std::optional<double> from;     // --from VALUE; default: the rig's value of KEY
  std::string start;              // --start A_1,..,A_N,psi_2,..,psi_N
  double step = 0.0;              // --step H (arclength); 0: |to - from| / 100
  int max_points = 500;           // per direction of each branch
  bool all = false;               // --all: every locked state at the start value
  std::string out;                // --out DIR; empty: runs/<rig name>-continue
  bool quiet = false;
  bool strict = false;     // --strict: sensible ranges (docs/sensible-ranges.md)
  bool no_cycles = false;  // --no-cycles
  int cycle_points = 100;  // --cycle-points: each limit cycle's point budget
  std::string fold_key;    // --fold KEY2: continue each fold in KEY and KEY2
  double to2 = 0.0;        // --to2 VALUE: KEY2's other end (it starts at the rig's value)
};

// The rig with --set, then `extra` (the parameter's KEY=VALUE, named --param in messages; keys
// as in docs/keys.md: metronomes.*.X sets X of every metronome). Throws RigError.
Rig loadContinueRig(const ContinueOptions& opt, const std::vector<std::string>& extra);

}  // namespace metrosync::cli
