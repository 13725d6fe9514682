#include "tools/bench/careful_peer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "base/number_text.h"
#include "tools/bench/peer_output.h"
#include "tools/bench/peer_scene.h"
#include "tools/bench/subprocess.h"

#ifndef METROSYNC_SOURCE_DIR
#define METROSYNC_SOURCE_DIR "."
#endif

namespace metrosync::bench {

namespace {

namespace fs = std::filesystem;

// The build script compiles the peer (about 40 s the first time): allow it that and more.
constexpr double kBuildTimeoutS = 600;
// The peer's final time against the scene's: the same number written with 17 digits, read back
constexpr double kEndTimeSlack = 1e-12;

std::string& givenPath() {
  static std::string p;
  return p;
}

std::string firstLine(const std::string& s) {
  const size_t end = s.find('\n');
  return s.substr(0, end == std::string::npos ? s.size() : end);
}

// The main checkout of a git worktree (its .git is a file "gitdir: MAIN/.git/worktrees/NAME"),
// or "" when `source_dir` is not a worktree.
std::string mainCheckout(const std::string& source_dir) {
  std::ifstream f(fs::path(source_dir) / ".git");
  std::string line;
  if (!f || !std::getline(f, line) || line.rfind("gitdir: ", 0) != 0) return "";
  const std::string gitdir = line.substr(8);
  const size_t at = gitdir.find("/.git/worktrees/");
  return at == std::string::npos ? "" : gitdir.substr(0, at);
}

PeerLocation checkBinary(const std::string& path, const std::string& how) {
  if (::access(path.c_str(), X_OK) == 0) return {path, "", how};
  return {"", how + " names " + path + ", which is not an executable file", how};
}

PeerLocation locate() {
  if (!givenPath().empty()) return checkBinary(givenPath(), "--peer");
  if (const char* env = std::getenv("METROSYNC_PEER"); env && *env)
    return checkBinary(env, "METROSYNC_PEER");
  std::string looked;
  for (const std::string& script : peerBuildScripts(METROSYNC_SOURCE_DIR)) {
    if (!fs::exists(script)) {
      looked += (looked.empty() ? "" : ", ") + script;
      continue;
    }
    const ProcessResult r = runProcess({"bash", script}, kBuildTimeoutS);
    const std::string path = firstLine(r.out);
    if (!r.ok() || path.empty())
      return {"", script + " failed: " + firstLine(r.err.empty() ? r.error : r.err), script};
    return checkBinary(path, script);
  }
  return {"",
          "the careful peer is missing: no --peer PATH, no METROSYNC_PEER, and no build script (" +
              looked + "; the repository sits beside shared/ on the project's machines only)",
          ""};
}

// The peer's answer as the bench's run result (its timings are medians of its repeats).
RunResult fromPeer(const Scene& scene, const Method& m, const PeerOutput& p) {
  RunResult r;
  r.method = m;
  if (p.n != static_cast<int>(scene.rig.metronomes.size()))
    return failedRun(m, "the peer ran " + std::to_string(p.n) + " metronomes, the scene has " +
                            std::to_string(scene.rig.metronomes.size()));
  const double t_end = scene.rig.sim.t_end_s / scene.scaled.time_scale_s;
  if (!(std::abs(p.t - t_end) <= kEndTimeSlack * t_end))
    return failedRun(
        m, "the peer ended at t = " + std::to_string(p.t) + ", not at " + std::to_string(t_end));
  r.cpu_s = 1e-3 * p.cpu_ms;
  r.wall_s = 1e-3 * p.wall_ms;
  r.counts.steps = p.steps;
  r.counts.rhs_evals = p.rhs_calls;
  r.counts.events = p.events;
  r.counts.escapements = p.kicks;
  r.counts.stick_slip = p.stick_to_slip + p.slip_stops;  // every platform switch
  for (long k : p.kicks) r.ticks += k;
  r.final_state = benchFinalState(p.state);
  r.regime = "n/a (final state only)";
  return r;
}

}  // namespace

std::vector<std::string> peerBuildScripts(const std::string& source_dir) {
  std::vector<std::string> s = {
      (fs::path(source_dir) / ".." / "shared" / "peer" / "build.sh").lexically_normal().string()};
  if (const std::string main = mainCheckout(source_dir); !main.empty())
    s.push_back((fs::path(main) / ".." / "shared" / "peer" / "build.sh").lexically_normal());
  return s;
}

void setPeerPath(const std::string& path) {
  givenPath() = path;
}

const PeerLocation& peerLocation() {
  static const PeerLocation loc = locate();
  return loc;
}

std::vector<std::string> peerIntegratorNames() {
  return {"dopri5", "rkf78"};
}

PeerCall runCarefulPeer(const Scene& scene, const Method& method, int repeat, double timeout_s) {
  PeerCall call;
  const PeerLocation& loc = peerLocation();
  if (loc.path.empty()) {
    call.result = failedRun(method, loc.missing);
    return call;
  }
  const std::string tol = numberText(method.accuracy, 17);
  std::vector<std::string> argv = {loc.path};
  try {
    for (std::string& a : peerSceneArguments(scene)) argv.push_back(std::move(a));
  } catch (const std::invalid_argument& e) {
    call.result = failedRun(method, e.what());
    return call;
  }
  argv.insert(argv.end(), {"--method", method.integrator, "--rtol", tol, "--atol", tol, "--repeat",
                           std::to_string(std::max(1, repeat))});
  call.command = shellCommand(argv);
  const ProcessResult pr = runProcess(argv, timeout_s);
  if (!pr.ok()) {
    const std::string why = pr.timed_out ? "stopped after " + std::to_string(timeout_s) + " s"
                            : !pr.started
                                ? pr.error
                                : "exit " + std::to_string(pr.exit_code) + ": " + firstLine(pr.err);
    call.result = failedRun(method, "the peer failed (" + why + ")");
    call.result.over_budget = pr.timed_out;
    return call;
  }
  try {
    call.result = fromPeer(scene, method, parsePeerOutput(pr.out));
    call.runs = std::max(1, repeat);
  } catch (const std::invalid_argument& e) {
    call.result = failedRun(method, e.what());
  }
  return call;
}

}  // namespace metrosync::bench
