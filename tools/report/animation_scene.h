// What `metrosync animate` draws (docs/animate.md), as plain values: the Scene (the rig's
// drawable parts, the whole run's amplitude traces, the picture size), one FrameState per frame
// (the state at that instant), and the SceneLayout (where everything sits in pixels). Cairo is
// not needed here: the drawing itself is tools/report/animation.h.
//
// Everything is in the rig's physical units (a scaled rig as its equivalent physical system,
// models/scaling.h): metres, radians, seconds. One scale (pixels per metre) for the pendulums
// and the platforms' motion, so the picture is true to scale; no angle is exaggerated.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace metrosync::animation {

// How a platform's contact with what is under it is coloured.
enum class Contact { Smooth, Stuck, SlipPositive, SlipNegative };

struct SceneMetronome {
  std::string name;
  double length_m = 0.0;  // pivot to the pendulum's centre of mass (the bob)
  double theta_c = 0.0;   // escapement angle (rad)
  bool locked = false;    // held in its box: drawn upright with a bar
};

struct ScenePlatform {
  std::string name;
  int on = -1;                  // the platform it rests on; -1: the floor
  bool fixed = false;           // friction law `fixed`: on blocks, never moves
  bool coulomb = false;         // coloured by stick/slip
  bool ground_spring = false;   // a spring to a post on the floor
  std::vector<int> metronomes;  // indices into Scene::metronomes, left to right
};

struct SceneCoupling {
  int a = 0, b = 0;  // platforms joined by a spring
};

struct Scene {
  std::string title;
  bool physical = true;    // the clock shows seconds and tau; false (a scaled rig): tau only
  double tau_per_s = 1.0;  // slow time per second of the (equivalent) physical time
  std::vector<SceneMetronome> metronomes;  // global numbering (file order)
  std::vector<ScenePlatform> platforms;
  std::vector<SceneCoupling> couplings;
  double max_abs_x_m = 0.0;  // the largest platform excursion drawn (bounds the scale)
  int width = 1280, height = 720;

  // the amplitude traces: one row per trace point (scaled A_i, as envelope.csv), tau ascending
  double tau_from = 0.0, tau_to = 1.0;  // the traces' horizontal axis
  std::vector<double> trace_tau;
  std::vector<std::vector<double>> trace_A;  // (points x N)
  std::vector<double> theta_c_scaled;        // (N) the escapement angles in A's scale
};

// The state drawn in one frame.
struct FrameState {
  double t = 0.0;                // physical time (s; a scaled rig: scaled time)
  std::vector<double> x;         // (platforms) absolute position (m), 0 at rest
  std::vector<Contact> contact;  // (platforms)
  std::vector<double> theta;     // (N) pendulum angles (rad), 0 hanging
  std::vector<double> flash;     // (N) 0..1: 1 in the frame of a tick, fading after
  std::size_t trace_points = 0;  // trace rows drawn (those up to t)
};

struct Rect {
  double x = 0, y = 0, w = 0, h = 0;
};

// Pixel positions (origin top left, y down) with every platform at x = 0. In a frame, metronome
// i's pivot is moved by px_per_m * x of its platform, and its bob (the pendulum's centre of mass)
// is drawn at pivot + length_px[i] (sin theta_i, cos theta_i): it hangs below the pivot, as in
// the model; the needle drawn above the pivot is the metronome's rod.
struct SceneLayout {
  double px_per_m = 1.0;
  double unit_px = 1.0;  // the longest pendulum in pixels: boxes, boards and rollers scale with it
  double floor_y = 0.0;
  Rect stage, traces;
  struct Board {
    double left = 0, top = 0, width = 0, thickness = 0;
    double base_y = 0;  // where its rollers (or blocks) stand
    double roller_r = 0;
  };
  std::vector<Board> boards;             // (platforms)
  std::vector<double> pivot_x, pivot_y;  // (N) pivots with their platform at x = 0
  std::vector<double> length_px;         // (N)
  std::vector<int> platform_of;          // (N)
};

SceneLayout layoutScene(const Scene& scene);

}  // namespace metrosync::animation
