#include "tools/cli/animate.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "base/number_text.h"
#include "models/network_text.h"
#include "models/scaling.h"
#include "tools/cli/animate_plugin.h"
#include "tools/cli/animation_track.h"
#include "tools/cli/engines.h"
#include "tools/cli/number_option.h"
#include "tools/cli/range_warnings.h"
#include "tools/report/outputs.h"
#include "tools/report/plot.h"
#include "tools/report/video_pipe.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

// At most this many frames (an hour of video at 30 fps, 3.3 GB of raw frames per minute through
// the pipe at 1280x720): a larger request is almost surely a mistake in --speed or --fps.
constexpr long kMaxFrames = 108000;
// The index of a frame on the time line from t = 0 (--from on the frame grid) stays far inside a
// long: 2^53, where doubles still count every integer.
constexpr double kMaxFrameIndex = 9007199254740992.0;

struct Output {
  std::string path;
  bool gif = false;
};

Output checkOutput(const AnimateOptions& opt, const std::string& rig_name) {
  Output o;
  o.path = opt.out.empty() ? defaultOutputDir(rig_name, "animate") + ".mp4" : opt.out;
  std::string ext = std::filesystem::path(o.path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".mp4" && ext != ".gif")
    throw UsageError("--out " + o.path + ": unknown extension '" + ext +
                     "' (animate writes .mp4 or .gif)");
  o.gif = ext == ".gif";
  return o;
}

void parseSize(const AnimateOptions& opt, bool gif, AnimationRequest& req) {
  req.width = gif ? 640 : 1280;
  req.height = gif ? 360 : 720;
  if (opt.size.empty()) return;
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(opt.size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 64 || h < 64 ||
      w > 7680 || h > 4320 || w % 2 || h % 2)
    throw UsageError("--size " + opt.size +
                     ": expected WIDTHxHEIGHT, even numbers from 64x64 to 7680x4320");
  req.width = w;
  req.height = h;
}

// --speed, --fps, --from, --to in the rig's time unit, `unit` seconds (or scaled time) each.
void setTimes(const AnimateOptions& opt, double duration, double unit, AnimationRequest& req) {
  if (!(opt.speed > 0) || !std::isfinite(opt.speed))
    throw UsageError("--speed " + numberText(opt.speed) + ": must be > 0");
  const double to = std::isnan(opt.to) ? duration : opt.to;
  if (!(opt.from >= 0)) throw UsageError("--from " + numberText(opt.from) + ": must be >= 0");
  if (!(opt.from < to) || !std::isfinite(to))
    throw UsageError("--from " + numberText(opt.from) + " --to " + numberText(to) +
                     ": --from must be before --to");
  req.from = opt.from * unit;
  req.to = to * unit;
  req.speed = opt.speed * unit;
  // counted in double before any rounding to an integer: an extreme --speed or --to gives a
  // number of frames beyond every integer type, said as a double or as "more than" the largest
  const double frames = std::round((req.to - req.from) * req.fps / req.speed);
  // the first frame's index too: --from on a grid of frames finer than a long can count
  const double first = std::round(req.from / req.frameInterval());
  if (frames >= 1 && frames <= kMaxFrames && first < static_cast<double>(kMaxFrameIndex)) return;
  const std::string count =
      std::isfinite(frames) ? numberText(frames) : "more than " + numberText(DBL_MAX);
  if (!(first < static_cast<double>(kMaxFrameIndex)))
    throw UsageError(
        "--from " + numberText(opt.from) + " at --fps " + numberText(req.fps) + " / --speed " +
        numberText(opt.speed) + " is frame " +
        (std::isfinite(first) ? numberText(first) : "more than " + numberText(DBL_MAX)) +
        " of the video's time line: must be below " + numberText(kMaxFrameIndex));
  throw UsageError("--fps " + numberText(req.fps) + " x (" + numberText(to) + " - " +
                   numberText(opt.from) + ") / --speed " + numberText(opt.speed) + " = " + count +
                   " frames: must be 1 to " + std::to_string(kMaxFrames));
}

std::string displayName(const AnimateOptions& opt) {
  return opt.rig.rig_path.empty() ? "<default rig>" : opt.rig.rig_path;
}

std::string speedText(double speed, bool physical) {
  if (!physical) return "tau " + numberText(speed, 3) + " per second of video";
  return speed == 1.0 ? "real time" : "x" + numberText(speed, 3) + " speed";
}

}  // namespace

CLI::App* addAnimateCommand(CLI::App& app, AnimateOptions& opt) {
  CLI::App* cmd = app.add_subcommand(
      "animate", "draw the rig in motion (full model) into an MP4 or GIF video through ffmpeg");
  cmd->add_option(
      "RIG", opt.rig.rig_path,
      "rig file (YAML, docs/contract.md section 1, or a network of platforms); default: the "
      "built-in rig");
  cmd->add_option("--set", opt.rig.sets, "override a rig key, e.g. --set platform.friction.mu=0.3")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  cmd->add_option("--out", opt.out,
                  "the video: FILE.mp4 (H.264) or FILE.gif (default: runs/<rig name>-animate.mp4)")
      ->type_name("FILE");
  addNumber(cmd, "--speed", opt.speed, kPositive,
            "seconds of motion (a scaled rig: units of tau) per second of video")
      ->default_str("1");
  addNumber(cmd, "--fps", opt.fps, kPositive, "frames per second of video (default 30; GIF 20)");
  addNumber(cmd, "--from", opt.from, kNonNegative, "first instant drawn (s; a scaled rig: tau)")
      ->default_str("0");
  addNumber(cmd, "--to", opt.to, kPositive,
            "last instant (default: the rig's simulation.duration)");
  cmd->add_option("--size", opt.size, "frame size (default 1280x720; GIF 640x360)")
      ->type_name("WxH");
  cmd->add_option("--engine", opt.rig.engine, fullEngineHelp());
  cmd->add_flag("-q,--quiet", opt.rig.quiet, "no progress bar and no summary");
  addStrictFlag(cmd, opt.rig.strict);
  cmd->footer(
      "Frames: fps * (to - from) / speed of them, at the instants k * speed / fps from --from "
      "(rounded to that grid): each is a row of the run's trajectory. Exit codes: 0 success; 2 bad "
      "command line or rig, ffmpeg missing, or built without Cairo (nothing written); 3 the "
      "simulation failed (nothing written); 1 anything else.");
  return cmd;
}

bool animationAvailable() {
  return METROSYNC_HAVE_CAIRO;
}

namespace {

// The run and its frames: the rig (one platform, or a network of several) loaded once, on the
// full-model engine chosen for it as `run` chooses it.
AnimationTrack simulate(const AnimateOptions& opt, AnimationRequest& req, std::string& rig_name,
                        bool& physical) {
  const Options& o = opt.rig;
  const LoadOptions lo = engineLoadOptions(HUGE_VAL);  // animate writes no trajectory
  const std::string text = o.rig_path.empty() ? defaultRigYaml() : readRigFile(o.rig_path);
  const Network net = loadNetworkText(text, displayName(opt), o.sets, lo);
  checkSensibleRanges(text, displayName(opt), o.sets, o.strict);
  const Engine& engine = chooseEngine(o.engine, "full", net, displayName(opt), "animates");
  if (!net.isSingleRig()) {
    rig_name = net.name;
    setTimes(opt, net.sim.t_end_s, 1.0, req);
    req.title = net.name + " - " + networkOfPlatforms(net.platforms.size()) + " - " +
                engine.name() + " - " + speedText(opt.speed, true);
    return trackNetwork(net, engine, req);
  }
  const Rig rig = net.toSingleRig();  // the rig loadRigText gives
  rig_name = rig.name;
  const ScaledParams sp = computeScaled(rig);
  physical = rig.units == Units::Physical;
  // a scaled rig's times are in tau: t = tau / epsilon (its time_scale is 1)
  setTimes(opt, physical ? rig.sim.t_end_s : sp.tau_end,
           physical ? 1.0 : sp.time_scale_s / sp.epsilon, req);
  req.title = rig.name + " - " + engine.name() + " - " + speedText(opt.speed, physical);
  return trackRig(rig, engine, req);
}

}  // namespace

int animateCommand(const AnimateOptions& opt) {
  if (!animationAvailable())
    throw UsageError(
        "animate is unavailable: this metrosync was built without Cairo (install "
        "libcairo2-dev and configure again; docs/animate.md)");
  const std::string ffmpeg = findExecutable("ffmpeg");
  if (ffmpeg.empty())
    throw UsageError(
        "ffmpeg not found on PATH: animate encodes its video with ffmpeg (Debian "
        "package ffmpeg)");
  // the options first (a bad --out or --fps is said before the rig is read), then the run
  Output out;
  if (!opt.out.empty()) out = checkOutput(opt, "");
  if (!std::isnan(opt.fps) && !(opt.fps > 0 && std::isfinite(opt.fps)))
    throw UsageError("--fps " + numberText(opt.fps) + ": must be > 0");
  AnimationRequest req;
  req.fps = std::isnan(opt.fps) ? (out.gif ? 20.0 : 30.0) : opt.fps;
  parseSize(opt, out.gif, req);
  if (animationAvailable()) animatePlugin();  // Cairo now: a missing plugin before the run
  std::string rig_name;
  bool physical = true;
  const auto t0 = std::chrono::steady_clock::now();
  const AnimationTrack tr = simulate(opt, req, rig_name, physical);
  out = checkOutput(opt, rig_name);
  if (!tr.complete) {
    std::cerr << "metrosync: error: full model: " << tr.failure
              << "\nmetrosync: no video written\n";
    return kSimulationFailed;
  }
#if METROSYNC_HAVE_CAIRO
  animatePlugin().render(tr, {out.path, ffmpeg, req.width, req.height, req.fps, out.gif},
                         opt.rig.quiet);
  const double all_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double video_s = static_cast<double>(tr.frames.size()) / req.fps;
  // the motion shown, in the rig's time (seconds, or tau for a scaled rig), then the work's time
  const std::string motion = physical ? numberText(video_s * opt.speed, 4) + " s of motion"
                                      : "tau " + numberText(video_s * opt.speed, 4);
  if (!opt.rig.quiet)
    std::cout << out.path << ": " << tr.frames.size() << " frames, " << req.width << "x"
              << req.height << ", " << numberText(req.fps) << " fps, "
              << numberText(video_s, 2, Notation::Fixed) << " s of video showing " << motion
              << " (run and drawn in " << numberText(all_s, 3) << " s)\n";
#else
  (void)t0;  // not reached: animationAvailable() is false
#endif
  return kSuccess;
}

}  // namespace metrosync::cli
