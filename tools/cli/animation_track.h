// The motion `metrosync animate` draws (docs/animate.md): one run of the full model, sampled at
// the frame times. The frames are the run's trajectory rows: simulation.sample is set to the frame
// interval dt = speed / fps, so the engine takes a row at every k dt from its dense output (as
// every trajectory.csv row), and frame k is at (round(from / dt) + k) dt, bit for bit a row's
// time. Nothing is stepped twice. (A frame that fell between two rows would be the cubic Hermite
// interpolant of their values and rates; the engines of this build never leave one there.) Ticks
// come from the engine's events (one platform) or from the angles crossing theta_c outwards between
// samples (networks); amplitudes from the envelope rows (one platform) or from the samples
// (networks, as their envelope.csv).
#pragma once

#include <string>
#include <vector>

#include "models/network.h"
#include "models/rig.h"
#include "sim/engines/engine.h"
#include "tools/report/animation_scene.h"

namespace metrosync::cli {

// Times in the rig's physical seconds (a scaled rig: its scaled time t).
struct AnimationRequest {
  double from = 0.0, to = 0.0;
  double speed = 1.0;  // seconds of motion per second of video
  double fps = 30.0;
  int width = 1280, height = 720;
  std::string title;

  double frameInterval() const { return speed / fps; }
  // frames = fps (to - from) / speed, rounded; frame k is at
  // (firstFrameIndex() + k) * frameInterval(): `from` rounded to the frame grid
  long frameCount() const;
  long firstFrameIndex() const;
};

struct AnimationTrack {
  animation::Scene scene;
  std::vector<animation::FrameState> frames;  // frameCount() of them when complete
  std::vector<long> ticks;  // (N) ticks flashed over the whole run [0, to], per metronome
  bool complete = true;
  std::string failure;  // why the run stopped early
};

// One platform, on `engine` (a full-model engine); the rig's duration and sample are replaced.
AnimationTrack trackRig(Rig rig, const Engine& engine, const AnimationRequest& request);

// A network of several platforms, on `engine` (one that runs networks: direct or simbody); the
// network's duration and sample are replaced.
AnimationTrack trackNetwork(Network net, const Engine& engine, const AnimationRequest& request);

}  // namespace metrosync::cli
