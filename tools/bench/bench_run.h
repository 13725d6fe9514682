// One timed run of the full model on any engine, and its error against a reference run.
//   engines: "simbody" (sim/engines/simbody/simbody_engine.h), "direct"
//            (sim/engines/direct/direct_engine.h), "siconos" (tools/bench/siconos_peer.h, when
//            built with Siconos), "odeint" (tools/bench/odeint_peer.h, when built with Boost),
//            "peer" (the careful peer, a separate program: tools/bench/careful_peer.h), "run"
//            (`metrosync run` itself, the built binary: tools/bench/run_method.h)
//   sampling: a run either records the envelope (the envelope error's runs) or takes no samples
//            at all (RunSink::wantsEnvelope and wantsTrajectory false: the integrator and its
//            events only, what the final-state comparison times; the direct engine takes the
//            same steps and events and ends in the same state either way)
//   error:   on the envelope (max over rows of |A_i - A_i,ref| and of |psi_j - psi_j,ref| mod 2 pi,
//            scaled units) and on the final state (max of |dxdot|, |dtheta_i|, |dthetadot_i|,
//            scaled units; the platform's position x is left out: it is a drift coordinate that
//            no force depends on)
#pragma once

#include <string>
#include <vector>

#include "models/rig.h"
#include "tools/bench/bench_scene.h"

namespace metrosync::bench {

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});
Scene sceneFromRig(const std::string& name, const Rig& rig);

// "engine:integrator" or "engine:integrator:setting" (setting: the accuracy, or for siconos the
// steps per fast period). Throws std::invalid_argument for an unknown engine or integrator.
Method parseMethod(const std::string& spec);
// Every integrator of an engine that this binary can run, in its own order.
std::vector<std::string> integratorsOf(const std::string& engine);
bool engineAvailable(const std::string& engine);

// What a run records: the envelope (64 samples per fast period), or nothing but its final state.
enum class Sampling { Envelope, FinalState };

// Runs `scene` with `method` (the careful peer: one integration). The run is abandoned
// (over_budget) once it has taken more than budget_s of wall time (checked once per fast period
// while the envelope is recorded; the peer is stopped after budget_s).
RunResult runOnce(const Scene& scene, const Method& method, double budget_s,
                  Sampling sampling = Sampling::Envelope);

struct ErrorVsRef {
  double max_dA = 0.0;    // max over rows and metronomes of |A_i - A_i,ref|
  double max_dpsi = 0.0;  // max over rows and j of |psi_j - psi_j,ref| (mod 2 pi, in [0, pi])
  double envelope = 0.0;  // max of the two: the benchmark's error
  double final_state = 0.0;
  long rows = 0;  // rows compared (the shorter of the two runs)
};

ErrorVsRef compareRuns(const RunResult& run, const RunResult& ref);

// 1-minute load average (/proc/loadavg), NaN when unreadable.
double loadAverage1();

}  // namespace metrosync::bench
