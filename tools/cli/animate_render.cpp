// The plugin metrosync-animate.so (tools/cli/animate_plugin.h): animate's frames drawn with Cairo
// (tools/report/animation.h) and piped into ffmpeg (tools/report/video_pipe.h).
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "tools/cli/animate_plugin.h"
#include "tools/cli/commands.h"
#include "tools/report/animation.h"

namespace metrosync::cli {

namespace {

volatile sig_atomic_t g_stop = 0;
extern "C" void onAnimateSignal(int) {
  g_stop = 1;
}

// "[#####.....]  50%  900/1800 frames" redrawn in place on a terminal; elsewhere one line per
// tenth of the frames.
class Progress {
 public:
  Progress(long total, bool quiet) : total_(total), quiet_(quiet), tty_(::isatty(2)) {}
  void update(long done) {
    if (quiet_) return;
    const int pct = static_cast<int>(100 * done / total_);
    if (tty_ && pct != last_) {
      const int bar = pct / 4;
      std::fprintf(stderr, "\ranimate: [%s%s] %3d%% %ld/%ld frames", std::string(bar, '#').c_str(),
                   std::string(25 - bar, '.').c_str(), pct, done, total_);
      if (done == total_) std::fputc('\n', stderr);
    } else if (!tty_ && pct / 10 != last_ / 10) {
      std::fprintf(stderr, "animate: %3d%% (%ld/%ld frames)\n", pct / 10 * 10, done, total_);
    }
    last_ = pct;
  }

 private:
  long total_;
  bool quiet_, tty_;
  int last_ = -1;
};

void render(const AnimationTrack& tr, const VideoSpec& spec, bool quiet) {
  std::filesystem::path parent = std::filesystem::path(spec.path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec) throw UsageError("--out " + spec.path + ": cannot create " + parent.string());
  const animation::SceneLayout layout = animation::layoutScene(tr.scene);
  animation::Surface surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, spec.width, spec.height));
  g_stop = 0;
  signal(SIGINT, onAnimateSignal);
  signal(SIGTERM, onAnimateSignal);
  signal(SIGPIPE, SIG_IGN);  // a dead ffmpeg is a write error, reported with its log
  VideoPipe pipe(spec);
  Progress progress(static_cast<long>(tr.frames.size()), quiet);
  for (std::size_t k = 0; k < tr.frames.size(); ++k) {
    if (g_stop) throw std::runtime_error("interrupted by a signal: no video written");
    animation::drawFrame(surface.get(), tr.scene, layout, tr.frames[k]);
    pipe.write(cairo_image_surface_get_data(surface.get()),
               cairo_image_surface_get_stride(surface.get()));
    progress.update(static_cast<long>(k + 1));
  }
  pipe.finish();
}

}  // namespace

}  // namespace metrosync::cli

extern "C" const metrosync::cli::AnimatePlugin* metrosync_animate_plugin() {
  static const metrosync::cli::AnimatePlugin table{metrosync::cli::kAnimatePluginAbi,
                                                   &metrosync::cli::render};
  return &table;
}
