// `metrosync animate RIG [--out FILE.mp4|FILE.gif] [--speed X] [--fps N] [--from T --to T]`
// (docs/animate.md): one run of the full model drawn frame by frame (tools/report/animation.h,
// Cairo) and encoded by an ffmpeg child process (tools/report/video_pipe.h). Without Cairo at
// configure time the command is still there and says it is unavailable (exit 2).
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

#include "tools/cli/commands.h"

namespace metrosync::cli {

struct AnimateOptions {
  Options rig;         // RIG, --set, --engine, --quiet (the --out of `run` is not used)
  std::string out;     // FILE.mp4 or FILE.gif; empty: runs/<rig name>-animate.mp4
  double speed = 1.0;  // rig time units per second of video
  double fps = NAN;    // NaN: 30 for MP4, 20 for GIF
  double from = 0.0;   // in the rig's time unit (s; a scaled rig: tau)
  double to = NAN;     // NaN: the rig's duration
  std::string size;    // WxH; empty: 1280x720 (MP4), 640x360 (GIF)
};

CLI::App* addAnimateCommand(CLI::App& app, AnimateOptions& opt);

// Bad options, rig or a missing ffmpeg: UsageError / RigError (exit 2) before anything is
// written; a failed simulation: exit 3 with nothing written.
int animateCommand(const AnimateOptions& opt);

// Was this build made with Cairo (can animate draw)?
bool animationAvailable();

}  // namespace metrosync::cli
