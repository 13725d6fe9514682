#include "tools/report/animation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "base/constants.h"
#include "base/number_text.h"

namespace metrosync::animation {

namespace {

struct Rgb {
  double r, g, b;
};
// Paul Tol's "bright" and "muted" qualitative colours: told apart by colour-blind readers too
constexpr Rgb kPalette[] = {{0.267, 0.467, 0.667}, {0.933, 0.400, 0.467}, {0.133, 0.533, 0.200},
                            {0.800, 0.733, 0.267}, {0.400, 0.800, 0.933}, {0.667, 0.200, 0.467},
                            {0.200, 0.133, 0.533}, {0.067, 0.467, 0.200}, {0.600, 0.600, 0.200},
                            {0.533, 0.133, 0.333}};
constexpr Rgb kStuck{0.55, 0.60, 0.68}, kSlip{0.90, 0.45, 0.15}, kSmooth{0.72, 0.60, 0.45};
constexpr Rgb kInk{0.15, 0.15, 0.18}, kBackground{0.98, 0.98, 0.97}, kFlash{1.0, 0.85, 0.1};

void setColor(cairo_t* cr, const Rgb& c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

Rgb colorOf(int i) {
  return kPalette[i % (sizeof kPalette / sizeof kPalette[0])];
}

void text(cairo_t* cr, double x, double y, double size, const std::string& s, bool bold = false) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
  cairo_new_path(cr);  // no line from the text's end to what is drawn next
}

// A zigzag spring from (x0, y0) to (x1, y1) with `coils` turns and half-width w.
void spring(cairo_t* cr, double x0, double y0, double x1, double y1, double w, int coils = 8) {
  const double dx = x1 - x0, dy = y1 - y0, len = std::hypot(dx, dy);
  if (len <= 0) return;
  const double nx = -dy / len, ny = dx / len;
  cairo_move_to(cr, x0, y0);
  const int n = 2 * coils;
  for (int k = 0; k <= n; ++k) {
    const double f = 0.1 + 0.8 * k / n, side = (k == 0 || k == n) ? 0 : (k % 2 ? 1 : -1);
    cairo_line_to(cr, x0 + f * dx + side * w * nx, y0 + f * dy + side * w * ny);
  }
  cairo_line_to(cr, x1, y1);
  cairo_stroke(cr);
}

Rgb contactColor(const ScenePlatform& p, Contact c) {
  if (!p.coulomb) return kSmooth;
  return c == Contact::Stuck ? kStuck : kSlip;
}

// What the board stands on: rollers (turning as they roll: a roller under a board that moved x
// has turned x / (2 r)), blocks for a fixed board, a deck for a board on another board.
void drawSupport(cairo_t* cr, const ScenePlatform& p, const SceneLayout::Board& b, double dx,
                 double x_m, double px_per_m) {
  const double r = b.roller_r, cy = b.base_y - r;
  cairo_set_line_width(cr, std::max(1.0, 0.2 * r));
  for (double f : {0.15, 0.5, 0.85}) {
    if (p.fixed) {
      setColor(cr, kInk, 0.8);
      cairo_rectangle(cr, b.left + f * b.width - r, b.base_y - 2 * r, 2 * r, 2 * r);
      cairo_fill(cr);
      continue;
    }
    // the rollers' centres move half as far as the board
    const double cx = b.left + f * b.width + dx / 2, turn = x_m * px_per_m / (2 * r);
    setColor(cr, {0.85, 0.85, 0.85});
    cairo_arc(cr, cx, cy, r, 0, 2 * kPi);
    cairo_fill_preserve(cr);
    setColor(cr, kInk);
    cairo_stroke(cr);
    cairo_move_to(cr, cx, cy);
    cairo_line_to(cr, cx + r * std::sin(turn), cy - r * std::cos(turn));
    cairo_stroke(cr);
  }
}

void drawGroundSpring(cairo_t* cr, const SceneLayout::Board& b, double dx) {
  // the post stands beyond the board's largest excursion (tools/report/animation_scene.cpp)
  const double post_x = b.left - 0.075 * b.width, y = b.top + 0.5 * b.thickness;
  setColor(cr, kInk);
  cairo_set_line_width(cr, 3);
  cairo_move_to(cr, post_x, b.base_y);
  cairo_line_to(cr, post_x, b.top - b.thickness);
  cairo_stroke(cr);
  cairo_set_line_width(cr, 1.5);
  spring(cr, post_x, y, b.left + dx, y, 0.4 * b.thickness, 6);
}

}  // namespace

void metronomeColor(int i, double rgb[3]) {
  const Rgb c = colorOf(i);
  rgb[0] = c.r, rgb[1] = c.g, rgb[2] = c.b;
}

namespace {

void drawPlatform(cairo_t* cr, const Scene& s, const SceneLayout& lay, const FrameState& st,
                  int p) {
  const ScenePlatform& plat = s.platforms[p];
  const SceneLayout::Board& b = lay.boards[p];
  const double dx = lay.px_per_m * st.x[p];
  if (plat.ground_spring) drawGroundSpring(cr, b, dx);
  drawSupport(cr, plat, b, dx, st.x[p], lay.px_per_m);
  setColor(cr, contactColor(plat, st.contact[p]));
  cairo_rectangle(cr, b.left + dx, b.top, b.width, b.thickness);
  cairo_fill_preserve(cr);
  setColor(cr, kInk);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  // a deck on posts for the platforms that rest on this one
  for (const ScenePlatform& q : s.platforms) {
    if (&q == &plat || q.on != p) continue;
    const SceneLayout::Board& up = lay.boards[&q - &s.platforms[0]];
    setColor(cr, kInk, 0.7);
    cairo_rectangle(cr, b.left + dx, up.base_y, b.width, 0.5 * up.roller_r);
    cairo_rectangle(cr, b.left + dx, up.base_y, 0.5 * up.roller_r, b.top - up.base_y);
    cairo_rectangle(cr, b.left + dx + b.width - 0.5 * up.roller_r, up.base_y, 0.5 * up.roller_r,
                    b.top - up.base_y);
    cairo_fill(cr);
  }
  text(cr, b.left + dx + 4, b.top + b.thickness - 2, std::min(0.9 * b.thickness, 14.0), plat.name);
}

// The box (a trapezoid), the flash of a tick at its top, the needle above the pivot and the bob
// (the pendulum's centre of mass) L below it.
void drawMetronome(cairo_t* cr, const Scene& s, const SceneLayout& lay, const FrameState& st,
                   int i) {
  const double u = lay.unit_px, dx = lay.px_per_m * st.x[lay.platform_of[i]];
  const double px = lay.pivot_x[i] + dx, py = lay.pivot_y[i];
  const double bottom = py + 1.5 * u, top = py - 1.1 * u;
  cairo_move_to(cr, px - 1.0 * u, bottom);
  cairo_line_to(cr, px + 1.0 * u, bottom);
  cairo_line_to(cr, px + 0.55 * u, top);
  cairo_line_to(cr, px - 0.55 * u, top);
  cairo_close_path(cr);
  setColor(cr, {0.93, 0.90, 0.84});
  cairo_fill_preserve(cr);
  setColor(cr, kInk);
  cairo_set_line_width(cr, std::max(1.0, 0.05 * u));
  cairo_stroke(cr);
  if (st.flash[i] > 0) {
    setColor(cr, kFlash, st.flash[i]);
    cairo_arc(cr, px, top - 0.25 * u, 0.3 * u, 0, 2 * kPi);
    cairo_fill(cr);
  }
  const double th = s.metronomes[i].locked ? 0.0 : st.theta[i];
  cairo_set_line_width(cr, std::max(1.5, 0.08 * u));
  setColor(cr, kInk);
  cairo_move_to(cr, px, py);
  cairo_line_to(cr, px - 2.8 * u * std::sin(th), py - 2.8 * u * std::cos(th));
  cairo_stroke(cr);
  if (s.metronomes[i].locked) {
    cairo_move_to(cr, px - 0.4 * u, py - 0.5 * u);
    cairo_line_to(cr, px + 0.4 * u, py - 0.5 * u);
    cairo_stroke(cr);
  }
  const double bx = px + lay.length_px[i] * std::sin(th), by = py + lay.length_px[i] * std::cos(th);
  cairo_move_to(cr, px, py);
  cairo_line_to(cr, bx, by);
  cairo_stroke(cr);
  setColor(cr, colorOf(i));
  cairo_arc(cr, bx, by, std::max(3.0, 0.2 * u), 0, 2 * kPi);
  cairo_fill(cr);
}

// A coupling spring between the facing edges of two boards (level with them).
void drawCoupling(cairo_t* cr, const SceneLayout& lay, const FrameState& st,
                  const SceneCoupling& c) {
  const SceneLayout::Board &a = lay.boards[c.a], &b = lay.boards[c.b];
  const double xa = a.left + lay.px_per_m * st.x[c.a], xb = b.left + lay.px_per_m * st.x[c.b];
  const bool a_left = a.left <= b.left;
  const double x0 = a_left ? xa + a.width : xa, x1 = a_left ? xb : xb + b.width;
  const double y0 = a.top + 0.5 * a.thickness, y1 = b.top + 0.5 * b.thickness;
  setColor(cr, {0.2, 0.35, 0.6});
  cairo_set_line_width(cr, 1.5);
  spring(cr, x0, y0, x1, y1, 0.6 * std::max(a.thickness, b.thickness), 7);
}

void drawClock(cairo_t* cr, const Scene& s, const SceneLayout& lay, const FrameState& st) {
  const double H = s.height, size = 0.035 * H, tau = st.t * s.tau_per_s;
  setColor(cr, kInk);
  text(cr, 0.02 * H, 0.055 * H, 0.04 * H, s.title, true);
  std::string clock = "tau = " + numberText(tau, 3, Notation::Fixed);
  const std::string t = numberText(st.t, 2, Notation::Fixed);
  if (s.physical)
    clock =
        "t = " + std::string(t.size() < 7 ? 7 - t.size() : 0, ' ') + t + " s    " + clock;  // %7.2f
  text(cr, 0.02 * H, 0.10 * H, size, clock);
  if (!s.physical) return;
  // a stopwatch dial in the stage's top right corner: the hand turns once a minute
  const double r = 0.05 * H, cx = lay.stage.x + lay.stage.w - 1.2 * r, cy = lay.stage.y + 1.2 * r;
  const double a = 2 * kPi * st.t / 60.0;
  cairo_set_line_width(cr, 1.5);
  cairo_new_path(cr);
  cairo_arc(cr, cx, cy, r, 0, 2 * kPi);
  cairo_stroke(cr);
  for (int k = 0; k < 12; ++k) {
    const double b = 2 * kPi * k / 12;
    cairo_move_to(cr, cx + 0.8 * r * std::sin(b), cy - 0.8 * r * std::cos(b));
    cairo_line_to(cr, cx + r * std::sin(b), cy - r * std::cos(b));
  }
  cairo_move_to(cr, cx, cy);
  cairo_line_to(cr, cx + 0.9 * r * std::sin(a), cy - 0.9 * r * std::cos(a));
  cairo_stroke(cr);
}

void drawLegend(cairo_t* cr, const Scene& s, const SceneLayout& lay) {
  const double size = 0.025 * s.height, x = lay.traces.x, y0 = lay.traces.y + lay.traces.h;
  double y = y0 + 3.2 * size;
  bool coulomb = false;
  for (const ScenePlatform& p : s.platforms) coulomb = coulomb || p.coulomb;
  const auto swatch = [&](const Rgb& c, const std::string& label) {
    setColor(cr, c);
    cairo_rectangle(cr, x, y - 0.8 * size, 1.6 * size, 0.8 * size);
    cairo_fill(cr);
    setColor(cr, kInk);
    text(cr, x + 2.2 * size, y, size, label);
    y += 1.4 * size;
  };
  if (coulomb) swatch(kStuck, "platform stuck"), swatch(kSlip, "platform slipping");
  if (!coulomb) swatch(kSmooth, "platform (no dry friction)");
  swatch(kFlash, "tick (escapement impulse)");
  const std::size_t n = s.metronomes.size();
  if (n > 8) return;
  for (std::size_t i = 0; i < n; ++i) swatch(colorOf(static_cast<int>(i)), s.metronomes[i].name);
}

void drawAxes(cairo_t* cr, const Scene& s, const Rect& r, double a_max) {
  const double size = 0.024 * s.height;
  setColor(cr, {1, 1, 1});
  cairo_rectangle(cr, r.x, r.y, r.w, r.h);
  cairo_fill_preserve(cr);
  setColor(cr, kInk);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  text(cr, r.x, r.y - 0.6 * size, size, "amplitudes A_i (scaled), dashed: theta_c");
  text(cr, r.x - 0.3 * size, r.y + r.h + 1.3 * size, size, numberText(s.tau_from, 3));
  text(cr, r.x + r.w - 2.5 * size, r.y + r.h + 1.3 * size, size, numberText(s.tau_to, 3));
  text(cr, r.x + 0.45 * r.w, r.y + r.h + 1.3 * size, size, "tau");
  text(cr, r.x + 0.3 * size, r.y + 1.1 * size, size, numberText(a_max, 3));
  static const double dash[] = {4.0, 4.0};
  cairo_set_dash(cr, dash, 2, 0);
  for (double tc : s.theta_c_scaled) {
    const double y = r.y + r.h * (1 - tc / a_max);
    cairo_move_to(cr, r.x, y);
    cairo_line_to(cr, r.x + r.w, y);
  }
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0);
}

void drawTraces(cairo_t* cr, const Scene& s, const SceneLayout& lay, const FrameState& st) {
  const Rect& r = lay.traces;
  double a_max = 0.0;
  for (const auto& row : s.trace_A)
    for (double a : row) a_max = std::max(a_max, a);
  for (double tc : s.theta_c_scaled) a_max = std::max(a_max, tc);
  a_max = a_max > 0 ? 1.1 * a_max : 1.0;
  drawAxes(cr, s, r, a_max);
  const double span = s.tau_to > s.tau_from ? s.tau_to - s.tau_from : 1.0;
  const auto X = [&](double tau) { return r.x + r.w * (tau - s.tau_from) / span; };
  const auto Y = [&](double a) { return r.y + r.h * (1 - a / a_max); };
  const std::size_t n = std::min(st.trace_points, s.trace_tau.size());
  cairo_set_line_width(cr, 1.5);
  for (std::size_t i = 0; i < s.metronomes.size(); ++i) {
    setColor(cr, colorOf(static_cast<int>(i)));
    for (std::size_t k = 0; k < n; ++k)
      (k ? cairo_line_to : cairo_move_to)(cr, X(s.trace_tau[k]), Y(s.trace_A[k][i]));
    cairo_stroke(cr);
  }
  setColor(cr, kInk, 0.5);
  const double now = X(std::clamp(st.t * s.tau_per_s, s.tau_from, s.tau_to));
  cairo_move_to(cr, now, r.y);
  cairo_line_to(cr, now, r.y + r.h);
  cairo_stroke(cr);
}

}  // namespace

void drawFrame(cairo_surface_t* target, const Scene& s, const SceneLayout& lay,
               const FrameState& st) {
  cairo_t* cr = cairo_create(target);
  setColor(cr, kBackground);
  cairo_paint(cr);
  setColor(cr, kInk);
  cairo_set_line_width(cr, 2);
  cairo_move_to(cr, lay.stage.x, lay.floor_y);
  cairo_line_to(cr, lay.stage.x + lay.stage.w, lay.floor_y);
  cairo_stroke(cr);
  for (std::size_t p = 0; p < s.platforms.size(); ++p)
    drawPlatform(cr, s, lay, st, static_cast<int>(p));
  for (const SceneCoupling& c : s.couplings) drawCoupling(cr, lay, st, c);
  for (std::size_t i = 0; i < s.metronomes.size(); ++i)
    drawMetronome(cr, s, lay, st, static_cast<int>(i));
  drawClock(cr, s, lay, st);
  drawTraces(cr, s, lay, st);
  drawLegend(cr, s, lay);
  cairo_destroy(cr);
  cairo_surface_flush(target);
}

Surface frame(const Scene& scene, const SceneLayout& layout, const FrameState& state) {
  Surface s(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, scene.width, scene.height));
  drawFrame(s.get(), scene, layout, state);
  return s;
}

}  // namespace metrosync::animation
