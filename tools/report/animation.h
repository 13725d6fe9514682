// The frames of `metrosync animate` (docs/animate.md), drawn with Cairo: the rig at one instant
// (platforms on rollers, blocks or springs, coloured by stick/slip; metronome boxes; pendulums at
// their angles; a flash at each tick; coupling springs), a clock (seconds and tau) and the
// amplitude traces up to that instant. A pure function of (scene, state): no file, no clock.
// Built only when Cairo is found at configure time (tools/report/animation.cmake).
#pragma once

#include <cairo.h>

#include <memory>

#include "tools/report/animation_scene.h"

namespace metrosync::animation {

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;

// A new scene.width x scene.height ARGB32 image surface with the frame drawn on it.
Surface frame(const Scene& scene, const SceneLayout& layout, const FrameState& state);

// The same into an existing surface of that size (the renderer reuses one per frame).
void drawFrame(cairo_surface_t* target, const Scene& scene, const SceneLayout& layout,
               const FrameState& state);

// The colour metronome i's bob and trace are drawn in (r, g, b in 0..1).
void metronomeColor(int i, double rgb[3]);

}  // namespace metrosync::animation
