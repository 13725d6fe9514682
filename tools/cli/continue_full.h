// `metrosync continue RIG --model full --param KEY --to VALUE [--from V] [--step H]
// [--max-points M] [--out DIR]`: the full model's locked states as periodic orbits, followed in
// one rig key (sim/analysis/periodic_orbit/, docs/continuation.md). Dispatched from
// tools/cli/continue.cpp; the slow-flow options --start, --all, --fold and --no-cycles do not
// apply (exit 2).
#pragma once

#include "tools/cli/continue_options.h"

namespace metrosync::cli {

// The exit code (SPEC 5); bad input (an unknown key, a key without effect on the full model, a
// rig whose start does not settle onto a periodic orbit) throws RigError or UsageError (exit 2)
// before anything is written.
int continueFullCommand(const ContinueOptions& opt);

}  // namespace metrosync::cli
