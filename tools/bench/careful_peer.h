// The careful peer (../shared/peer: an independent C++17 program on Boost.Odeint, the same scaled
// equations and event semantics) as methods of the bench, "peer:dopri5" and "peer:rkf78": run as
// a subprocess on a scene's peer arguments (tools/bench/peer_scene.h), its --repeat K
// integrations timed inside its own process (CPU median, integration only), its final state
// mapped to the bench's. It is not part of the project and not on every machine (CI has no
// shared/): when it is missing, the bench says why and the methods are unavailable.
#pragma once

#include <string>
#include <vector>

#include "tools/bench/bench_scene.h"

namespace metrosync::bench {

// Where the peer's binary is: `path`, or "" and why not.
struct PeerLocation {
  std::string path;
  std::string missing;
  std::string how;  // how it was found: "--peer", "METROSYNC_PEER", or the build script run
};

// The peer's binary given on the command line (--peer PATH); overrides the rest. Call before
// the first peerLocation().
void setPeerPath(const std::string& path);

// Resolved once per process: --peer PATH, else $METROSYNC_PEER, else the output of
// `bash DIR/shared/peer/build.sh` (which builds the peer if needed and prints its path) for DIR
// the directory that holds this source tree (or, for a git worktree, the main checkout's).
const PeerLocation& peerLocation();

// The build scripts looked for, in order, for a source tree at `source_dir` (exposed for tests).
std::vector<std::string> peerBuildScripts(const std::string& source_dir);

// The peer's methods: dopri5, rkf78.
std::vector<std::string> peerIntegratorNames();

// One call of the peer on `scene` with `method` (its accuracy is the peer's --rtol and --atol)
// and --repeat `repeat`: the result has the peer's CPU and wall medians in cpu_s and wall_s, its
// counts, and the final state in the bench's form. A failure (the peer missing, its exit, its
// output) is complete = false with the reason. timeout_s > 0 stops the peer after that long.
struct PeerCall {
  RunResult result;
  int runs = 0;         // integrations behind the medians
  std::string command;  // the command line run
};
PeerCall runCarefulPeer(const Scene& scene, const Method& method, int repeat, double timeout_s);

}  // namespace metrosync::bench
