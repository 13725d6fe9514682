// `metrosync animate` (docs/animate.md): the video's frame count and duration as ffprobe reads
// them (frames = fps * (to - from) / speed), MP4 and GIF, one platform and a network; a frame
// drawn at a known state has each bob where the geometry puts it (pixels read back from the
// Cairo surface); the frames are the run's own trajectory rows; bad input exits 2 with nothing
// written.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/engine.h"
#include "tests/common/run_metrosync.h"
#include "tools/cli/animate.h"
#include "tools/cli/animation_track.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"
#if METROSYNC_HAVE_CAIRO
#include "tools/report/animation.h"
#endif

namespace metrosync {
namespace {

namespace fs = std::filesystem;
using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;

const std::string kRigs = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/";

// ffprobe's count of decoded frames and the container's duration (s).
struct Probe {
  long frames = -1;
  double duration = -1;
};

Probe probe(const std::string& path) {
  const std::string cmd =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames -show_entries format=duration -of "
      "default=noprint_wrappers=1 " +
      shellQuote(path);
  Probe p;
  FILE* f = ::popen(cmd.c_str(), "r");
  if (!f) return p;
  char line[256];
  while (std::fgets(line, sizeof line, f)) {
    const std::string l(line);
    if (l.rfind("nb_read_frames=", 0) == 0) p.frames = std::stol(l.substr(15));
    if (l.rfind("duration=", 0) == 0) p.duration = std::stod(l.substr(9));
  }
  ::pclose(f);
  return p;
}

std::size_t filesIn(const std::string& dir) {
  if (!fs::exists(dir)) return 0;
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), {}));
}

#if !METROSYNC_HAVE_CAIRO

// A build without Cairo (CI has it: tools/setup.sh installs libcairo2-dev): the command is there,
// says it is unavailable, exits 2 and writes nothing.
TEST(Animate, SaysItIsUnavailableWithoutCairo) {
  EXPECT_FALSE(cli::animationAvailable());
  const std::string dir = scratchDir("animate", "nocairo");
  const auto r = runMetrosync("animate --to 1 --out " + shellQuote(dir + "/v.mp4"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("animate is unavailable"), std::string::npos) << r.err;
  EXPECT_EQ(filesIn(dir), 0u);
}

#else

struct VideoCase {
  std::string rig, ext, options;
  long frames;      // fps * (to - from) / speed
  double duration;  // frames / fps
};

TEST(Animate, FfprobeCountsFpsTimesDurationOverSpeed) {
  const std::vector<VideoCase> cases = {
      {"", "mp4", "--to 2 --fps 15 --speed 0.5", 60, 4.0},         // slow motion
      {"", "mp4", "--from 1 --to 5 --fps 12 --speed 2", 24, 2.0},  // fast, from an offset
      {kRigs + "two-boards-rollers.yaml", "mp4", "--to 1 --fps 24", 24, 1.0},  // a network
      {"", "gif", "--to 1.5 --fps 10", 15, 1.5},  // palettegen/paletteuse
  };
  for (const VideoCase& c : cases) {
    const std::string dir = scratchDir("animate", "probe", true);
    const std::string out = dir + "/video." + c.ext;
    const auto r = runMetrosync("animate " + (c.rig.empty() ? "" : shellQuote(c.rig)) + " " +
                                c.options + " --size 320x180 --out " + shellQuote(out));
    ASSERT_EQ(r.code, 0) << c.options << "\n" << r.err;
    EXPECT_NE(r.err.find("100%"), std::string::npos) << "progress lines on stderr:\n" << r.err;
    const Probe p = probe(out);
    EXPECT_EQ(p.frames, c.frames) << c.options;
    EXPECT_NEAR(p.duration, c.duration, 0.011) << c.options;
    EXPECT_EQ(filesIn(dir), 1u) << "only the video, no temporary file left: " << c.options;
    if (c.ext == "gif") {
      EXPECT_EQ(testing_support::slurp(out).substr(0, 6), "GIF89a");
    }
  }
}

TEST(Animate, BadInputExitsTwoWithNothingWritten) {
  const std::string empty_path = scratchDir("animate", "nopath", true);
  const std::map<std::string, std::string> cases = {
      {"--to 1 --out DIR/v.avi", "unknown extension"},
      {"--to 1 --fps 0 --out DIR/v.mp4", "--fps 0: must be a number > 0"},
      {"--to 1 --fps -5 --out DIR/v.mp4", "--fps -5: must be a number > 0"},
      {"--to 1 --speed 0 --out DIR/v.mp4", "--speed 0: must be a number > 0"},
      {"--from 2 --to 1 --out DIR/v.mp4", "--from must be before --to"},
      {"--from 1 --to 1 --out DIR/v.mp4", "--from must be before --to"},
      {"--to 1 --size 321x180 --out DIR/v.mp4", "--size 321x180"},
      {"--to 1 --set platform.mass=-1 --out DIR/v.mp4", "platform.mass"},
      {"--to 1 --engine slowflow --out DIR/v.mp4", "slowflow"},
  };
  for (const auto& [pattern, message] : cases) {
    std::string args = pattern;
    const std::string dir = scratchDir("animate", "bad");
    args.replace(args.find("DIR"), 3, dir);
    const auto r = runMetrosync("animate " + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(filesIn(dir), 0u) << args;
  }
  // ffmpeg missing: a PATH without it
  const std::string dir = scratchDir("animate", "noffmpeg");
  const auto r = runMetrosync("animate --to 1 --out " + shellQuote(dir + "/v.mp4"),
                              {"", "PATH=" + shellQuote(empty_path)});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("ffmpeg not found"), std::string::npos) << r.err;
  EXPECT_EQ(filesIn(dir), 0u);
}

#endif  // METROSYNC_HAVE_CAIRO

// The frames are the rows of a run sampled every frame interval, bit for bit (one run, no
// re-stepping, no interpolation), also from a --from on or off the frame grid.
TEST(Animate, FramesAreTheRunsTrajectoryRows) {
  const Rig rig = defaultRig();
  const Engine& direct = *findEngine("direct");
  cli::AnimationRequest req;
  req.to = 1.0;
  req.fps = 30;
  const cli::AnimationTrack tr = cli::trackRig(rig, direct, req);
  ASSERT_TRUE(tr.complete);
  ASSERT_EQ(static_cast<long>(tr.frames.size()), req.frameCount());

  Rig sampled = rig;
  sampled.sim.t_end_s = 1.0;
  sampled.sim.sample_s = 1.0 / 30;
  MemorySink sink;
  direct.run(sampled, sink);
  for (std::size_t k = 0; k < tr.frames.size(); ++k) {
    ASSERT_EQ(sink.trajectory[k][0], tr.frames[k].t);
    EXPECT_EQ(sink.trajectory[k][1], tr.frames[k].x[0]);
    EXPECT_EQ(sink.trajectory[k][3], tr.frames[k].theta[0]);
    EXPECT_EQ(sink.trajectory[k][5], tr.frames[k].theta[1]);
  }
  // from 0.5 s (frame 15 of the grid) and from 0.51 s (rounded to it): rows 15, 16, ...
  for (double from : {0.5, 0.51}) {
    req.from = from;
    const cli::AnimationTrack later = cli::trackRig(rig, direct, req);
    ASSERT_EQ(later.frames.size(), 15u) << from;
    for (std::size_t k = 0; k < later.frames.size(); ++k) {
      ASSERT_EQ(sink.trajectory[15 + k][0], later.frames[k].t);
      EXPECT_EQ(sink.trajectory[15 + k][3], later.frames[k].theta[0]);
    }
  }
}

// Every escapement impulse is flashed on the metronome that ticked: the ticks attributed from
// one platform's event rows, and those detected between a network's samples, are the engines'
// own counts.
TEST(Animate, TicksAreTheEnginesTicks) {
  cli::AnimationRequest req;
  req.to = 3.0;
  const Rig rig = defaultRig();
  const cli::AnimationTrack tr = cli::trackRig(rig, *findEngine("direct"), req);
  Rig same = rig;
  same.sim.t_end_s = req.to;
  same.sim.sample_s = req.frameInterval();
  MemorySink sink;
  const RunReport rep = findEngine("direct")->run(same, sink);
  ASSERT_EQ(tr.ticks.size(), rep.counts.escapements.size());
  for (std::size_t i = 0; i < tr.ticks.size(); ++i) {
    EXPECT_GT(tr.ticks[i], 10) << i;
    EXPECT_EQ(tr.ticks[i], rep.counts.escapements[i]) << i;
  }

  Network net = loadNetworkFile(kRigs + "two-boards-rollers.yaml");
  const cli::AnimationTrack nt = cli::trackNetwork(net, *findEngine("direct"), req);
  net.sim.t_end_s = req.to;
  net.sim.sample_s = req.frameInterval();
  struct Discard : StateSink {
    void stateSample(double, const std::vector<double>&,
                     const std::vector<PlatformMode>&) override {}
  } discard;
  const RunReport nrep = runDirect(net, discard);
  ASSERT_EQ(nt.ticks.size(), nrep.counts.escapements.size());
  for (std::size_t i = 0; i < nt.ticks.size(); ++i)
    EXPECT_EQ(nt.ticks[i], nrep.counts.escapements[i]) << i;
}

// A network animates on the engine `run` would choose for it, Simbody's too (issue 38: every option
// the same on both kinds; main refused `animate NETWORK --engine simbody`): the same frames at the
// same times on both engines, their states agreeing to the engines' agreement at the rig's
// accuracy, and the same ticks.
TEST(Animate, ANetworkAnimatesOnEitherEngine) {
  cli::AnimationRequest req;
  req.to = 2.0;
  Network net = loadNetworkFile(kRigs + "two-boards-rollers.yaml");
  net.sim.accuracy = 1e-10;
  const cli::AnimationTrack d = cli::trackNetwork(net, *findEngine("direct"), req);
  const cli::AnimationTrack s = cli::trackNetwork(net, *findEngine("simbody"), req);
  ASSERT_TRUE(d.complete && s.complete) << d.failure << s.failure;
  ASSERT_EQ(d.frames.size(), static_cast<std::size_t>(req.frameCount()));
  ASSERT_EQ(s.frames.size(), d.frames.size());
  constexpr double kAgree = 1e-6;  // rad and m: the engines agree to ~1e-8 at accuracy 1e-10
  for (std::size_t k = 0; k < d.frames.size(); ++k) {
    ASSERT_EQ(d.frames[k].t, s.frames[k].t) << k;
    ASSERT_EQ(d.frames[k].x.size(), 2u);
    for (std::size_t p = 0; p < 2; ++p) EXPECT_NEAR(d.frames[k].x[p], s.frames[k].x[p], kAgree);
    for (std::size_t i = 0; i < d.frames[k].theta.size(); ++i)
      EXPECT_NEAR(d.frames[k].theta[i], s.frames[k].theta[i], kAgree) << k << " " << i;
  }
  EXPECT_EQ(d.ticks, s.ticks);
  EXPECT_GT(d.ticks.at(0), 2);
}

#if METROSYNC_HAVE_CAIRO

// ARGB32 pixel (x, y) as r, g, b in 0..255.
void pixel(cairo_surface_t* s, int x, int y, int rgb[3]) {
  const unsigned char* d = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  const std::uint32_t v = *reinterpret_cast<const std::uint32_t*>(d + y * stride + 4 * x);
  rgb[0] = (v >> 16) & 0xff, rgb[1] = (v >> 8) & 0xff, rgb[2] = v & 0xff;
}

bool isColor(cairo_surface_t* s, double x, double y, const double want[3]) {
  int rgb[3];
  pixel(s, static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)), rgb);
  for (int c = 0; c < 3; ++c)
    if (std::abs(rgb[c] - want[c] * 255) > 2) return false;
  return true;
}

TEST(Animate, BobIsDrawnWhereTheGeometryPutsIt) {
  animation::Scene sc;
  sc.metronomes = {{"A", 0.020, 0.2, false}, {"B", 0.030, 0.2, false}};
  animation::ScenePlatform p;
  p.name = "board";
  p.coulomb = true;
  p.metronomes = {0, 1};
  sc.platforms = {p};
  sc.max_abs_x_m = 0.01;
  const animation::SceneLayout lay = animation::layoutScene(sc);
  for (double x : {0.0, 0.009, -0.009}) {
    animation::FrameState st;
    st.x = {x};
    st.contact = {animation::Contact::SlipPositive};
    st.theta = {0.6, -0.35};
    st.flash = {0.0, 1.0};
    const animation::Surface surf = animation::frame(sc, lay, st);
    for (int i = 0; i < 2; ++i) {
      double want[3];
      animation::metronomeColor(i, want);
      // the pivot moves with the board; the bob hangs L_i below it at angle theta_i, one scale
      const double L = lay.px_per_m * sc.metronomes[i].length_m;
      const double bx = lay.pivot_x[i] + lay.px_per_m * x + L * std::sin(st.theta[i]);
      const double by = lay.pivot_y[i] + L * std::cos(st.theta[i]);
      EXPECT_TRUE(isColor(surf.get(), bx, by, want)) << "metronome " << i << ", x = " << x;
      // not at the mirror angle, nor where the board at rest would put it
      const double mx = lay.pivot_x[i] + lay.px_per_m * x - L * std::sin(st.theta[i]);
      EXPECT_FALSE(isColor(surf.get(), mx, by, want)) << i;
      if (x != 0) {
        EXPECT_FALSE(isColor(surf.get(), bx - lay.px_per_m * x, by, want)) << i;
      }
    }
  }
}

#endif

}  // namespace
}  // namespace metrosync
