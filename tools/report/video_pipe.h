// Encoding frames through an `ffmpeg` child process (docs/animate.md): raw BGRA frames are piped
// to its stdin; MP4 is H.264 (libx264, yuv420p), GIF goes through ffmpeg's palettegen and
// paletteuse (a lossless FFV1 intermediate and the palette are made in one pass, the GIF in a
// second, so no frame is held in memory). ffmpeg writes into a private temporary folder next to
// the output (sim/record/private_dir.h), reached through a descriptor; finish() renames the result
// into place, so an interrupted or failed encoding leaves nothing that looks complete. ffmpeg's own
// messages go to a log that finish() quotes on failure.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/record/private_dir.h"

namespace metrosync {

struct VideoSpec {
  std::string path;    // the output: *.mp4 or *.gif
  std::string ffmpeg;  // the executable
  int width = 0, height = 0;
  double fps = 30;
  bool gif = false;
};

class VideoPipe {
 public:
  // Starts ffmpeg; throws std::runtime_error when it cannot.
  explicit VideoPipe(const VideoSpec& spec);
  VideoPipe(const VideoPipe&) = delete;
  VideoPipe& operator=(const VideoPipe&) = delete;
  // Without finish(): stops ffmpeg and removes every temporary file.
  ~VideoPipe();

  // One frame: `height` rows of width * 4 bytes (B, G, R, A in memory order), `stride` bytes apart.
  // Throws std::runtime_error when ffmpeg has gone (its log quoted).
  void write(const unsigned char* data, int stride);
  // Closes the pipe, waits for ffmpeg (and runs the GIF's second pass), renames into place.
  // Throws std::runtime_error on failure (temporary files removed).
  void finish();

 private:
  void start(const std::vector<std::string>& args);
  void wait(const char* what);
  void cleanup();
  std::string logTail() const;

  VideoSpec spec_;
  std::unique_ptr<PrivateDir> tmp_;  // out, frames.mkv, palette.png, log
  pid_t child_ = -1;
  int fd_ = -1;
  bool finished_ = false;
};

}  // namespace metrosync
