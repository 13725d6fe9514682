// Issue 36's targets, where every part of the bench that measures or judges them finds them (the
// ratio against the careful peer is peer_verdict.h's kTargetRatio; the whole process's budget is
// process_phases.h's processBudget()).
#pragma once

namespace metrosync::bench {

// `run`'s wall_seconds within 15% of its engine's time (engine_seconds, and the engine alone)
constexpr double kRunOverEngineTarget = 1.15;
// one fit: at most this much wall time on 2 cores, and at most this many runs of the same rig
constexpr double kFitWallTargetS = 1.0;
constexpr double kFitOverRunTarget = 100;
// `continue --all` at N = 32: at most this much wall time on 2 cores
constexpr double kContinueTargetS = 20;

}  // namespace metrosync::bench
