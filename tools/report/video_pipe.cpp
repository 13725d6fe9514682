#include "tools/report/video_pipe.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "base/number_text.h"
#include "sim/record/atomic_file.h"
#include "sim/record/private_dir.h"

extern char** environ;

namespace metrosync {

namespace {

// Cairo's ARGB32 is a native-endian 32-bit word: B, G, R, A in memory on a little-endian machine.
const char* rawPixelFormat() {
  const std::uint32_t probe = 1;
  return *reinterpret_cast<const unsigned char*>(&probe) == 1 ? "bgra" : "argb";
}

// The input half of every first pass: raw frames on stdin.
std::vector<std::string> rawInput(const VideoSpec& s) {
  return {"-f",       "rawvideo",
          "-pix_fmt", rawPixelFormat(),
          "-s",       std::to_string(s.width) + "x" + std::to_string(s.height),
          "-r",       numberText(s.fps, 9),
          "-i",       "-"};
}

}  // namespace

VideoPipe::VideoPipe(const VideoSpec& spec) : spec_(spec) {
  try {
    // every file ffmpeg opens lies in a private folder it reaches through a descriptor
    // (sim/record/private_dir.h): nothing is reopened by a name someone else could replace
    const std::size_t slash = spec.path.rfind('/');
    tmp_ =
        std::make_unique<PrivateDir>(slash == std::string::npos ? "." : spec.path.substr(0, slash));
    tmp_->create("log");
    std::vector<std::string> args = rawInput(spec);
    if (spec.gif) {
      // pass 1: a lossless intermediate and the palette of all frames
      for (const char* a : {"-c:v", "ffv1", "-f", "matroska"}) args.push_back(a);
      args.push_back(PrivateDir::childPath("frames.mkv"));
      for (const char* a :
           {"-vf", "palettegen=stats_mode=full", "-frames:v", "1", "-update", "1", "-f", "image2"})
        args.push_back(a);
      args.push_back(PrivateDir::childPath("palette.png"));
    } else {
      for (const char* a : {"-c:v", "libx264", "-preset", "ultrafast", "-crf", "23", "-pix_fmt",
                            "yuv420p", "-movflags", "+faststart", "-f", "mp4"})
        args.push_back(a);
      args.push_back(PrivateDir::childPath("out"));
    }
    start(args);
  } catch (...) {
    cleanup();  // the temporaries made above
    throw;
  }
}

VideoPipe::~VideoPipe() {
  if (!finished_) cleanup();
}

void VideoPipe::start(const std::vector<std::string>& args) {
  std::vector<std::string> all{spec_.ffmpeg, "-hide_banner", "-loglevel",
                               "error",      "-nostdin",     "-y"};
  all.insert(all.end(), args.begin(), args.end());
  // -nostdin only stops ffmpeg reading commands from the terminal; "-i -" still reads frames
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const bool piped = std::find(args.begin(), args.end(), "-") != args.end();
  int fds[2] = {-1, -1};
  if (piped && ::pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + strerror(errno));
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (piped) {
    posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
    posix_spawn_file_actions_addclose(&fa, fds[1]);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
  } else {
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  }
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  const int log = tmp_->openForWriting("log");
  if (log < 0) {
    posix_spawn_file_actions_destroy(&fa);
    if (piped) ::close(fds[0]), ::close(fds[1]);
    throw std::runtime_error("cannot open ffmpeg's log in " + tmp_->path());
  }
  posix_spawn_file_actions_adddup2(&fa, log, 2);
  posix_spawn_file_actions_adddup2(&fa, tmp_->fd(), kChildDirFd);
  const int rc = posix_spawn(&child_, spec_.ffmpeg.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(log);
  if (piped) ::close(fds[0]);
  if (rc != 0) {
    if (piped) ::close(fds[1]);
    child_ = -1;
    throw std::runtime_error("cannot run " + spec_.ffmpeg + ": " + strerror(rc));
  }
  if (piped) fd_ = fds[1];
}

void VideoPipe::write(const unsigned char* data, int stride) {
  const std::size_t row = static_cast<std::size_t>(spec_.width) * 4;
  const auto put = [&](const unsigned char* p, std::size_t n) {
    while (n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0)
        throw std::runtime_error("ffmpeg stopped reading frames (" + std::string(strerror(errno)) +
                                 ")" + logTail());
      p += w;
      n -= static_cast<std::size_t>(w);
    }
  };
  if (static_cast<std::size_t>(stride) == row) {
    put(data, row * spec_.height);
    return;
  }
  for (int y = 0; y < spec_.height; ++y) put(data + static_cast<std::size_t>(y) * stride, row);
}

void VideoPipe::wait(const char* what) {
  int status = 0;
  while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  child_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(std::string("ffmpeg failed (") + what + ")" + logTail());
}

void VideoPipe::finish() {
  try {
    ::close(fd_);
    fd_ = -1;
    wait(spec_.gif ? "intermediate and palette" : "encoding");
    if (spec_.gif) {
      start({"-i", PrivateDir::childPath("frames.mkv"), "-i", PrivateDir::childPath("palette.png"),
             "-lavfi", "paletteuse=dither=bayer", "-f", "gif", PrivateDir::childPath("out")});
      wait("GIF");
    }
    if (!tmp_->publish("out", spec_.path))
      throw std::runtime_error("cannot rename ffmpeg's output to " + spec_.path + ": " +
                               strerror(errno));
  } catch (...) {
    cleanup();
    throw;
  }
  finished_ = true;
  tmp_.reset();  // the intermediate, the palette and the log
}

void VideoPipe::cleanup() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (child_ > 0) {
    ::kill(child_, SIGTERM);
    int status = 0;
    while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
    }
    child_ = -1;
  }
  tmp_.reset();  // every file ffmpeg wrote
}

std::string VideoPipe::logTail() const {
  std::string s = tmp_ ? tmp_->read("log") : "";
  if (s.size() > 2000) s = "..." + s.substr(s.size() - 2000);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s.empty() ? "" : ": " + s;
}

}  // namespace metrosync
