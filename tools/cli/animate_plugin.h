// `metrosync animate`'s drawing (Cairo, and through it fontconfig, freetype, X11's libraries) is
// the plugin metrosync-animate.so, which `metrosync` loads when animate runs
// (sim/engines/plugin_loader.h, docs/bench/process.md); test_animate links it directly.
#pragma once

#include "tools/cli/animation_track.h"
#include "tools/report/video_pipe.h"

namespace metrosync::cli {

inline constexpr const char* kAnimatePluginFile = "metrosync-animate.so";
constexpr int kAnimatePluginAbi = 1;  // raised whenever the table changes

struct AnimatePlugin {
  int abi = kAnimatePluginAbi;
  // Draws every frame of `track` and encodes them through ffmpeg into spec.path
  // (animate_render.cpp)
  void (*render)(const AnimationTrack& track, const VideoSpec& spec, bool quiet) = nullptr;
};

// The table, loading the plugin on the first call (thread-safe); throws PluginError when it
// cannot.
const AnimatePlugin& animatePlugin();

}  // namespace metrosync::cli

// The plugin's one entry point (animate_render.cpp).
extern "C" const metrosync::cli::AnimatePlugin* metrosync_animate_plugin();
