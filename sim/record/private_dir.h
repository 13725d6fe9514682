// A private temporary directory for the files another program (gnuplot, ffmpeg) writes or reads
// for metrosync (issue 29). Made with mkdtemp inside the output folder (so that the result is
// renamed into place on the same file system), opened without following a link and checked
// (fstat: a directory, the process's own, mode 0700), then used only through that descriptor:
// metrosync creates and renames its files relative to it (openat, renameat), and the child
// program inherits it as descriptor kChildDirFd and names the files /proc/self/fd/3/NAME. Nobody
// else can add, replace or remove a file in a 0700 directory, and replacing the directory itself
// (renaming it away, planting a link at its name) changes nothing the descriptor reaches: no file
// of it is ever reopened by a path someone else could replace.
#pragma once

#include <string>

namespace metrosync {

// The descriptor number the directory has in a child process (posix_spawn_file_actions_adddup2).
constexpr int kChildDirFd = 3;

class PrivateDir {
 public:
  // Makes `parent`/.metrosync-tmp.<pid>.XXXXXX; throws std::runtime_error when it cannot or when
  // what it opened is not the process's own 0700 directory.
  explicit PrivateDir(const std::string& parent);
  PrivateDir(const PrivateDir&) = delete;
  PrivateDir& operator=(const PrivateDir&) = delete;
  // Removes every file it holds (made here or by the child program) and itself.
  ~PrivateDir();

  // Creates NAME new in the directory with `contents`, closed (O_EXCL | O_NOFOLLOW).
  void create(const std::string& name, const std::string& contents = "");
  // Opens NAME new for writing (the descriptor is the caller's to close).
  int createOpen(const std::string& name);
  // Opens NAME (made by create) for appending; -1 when it cannot.
  int openForWriting(const std::string& name) const;
  // Opens NAME for reading (-1 when absent).
  int openForReading(const std::string& name) const;
  // The whole of NAME ("" when absent).
  std::string read(const std::string& name) const;
  // NAME's size in bytes (-1 when absent).
  long long size(const std::string& name) const;
  // Renames NAME to `final_path` (outside); false with errno set when it cannot.
  bool publish(const std::string& name, const std::string& final_path);
  // NAME as the child process sees it: /proc/self/fd/3/NAME.
  static std::string childPath(const std::string& name);

  int fd() const { return fd_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

// Is `name` (a file name in an output folder) a private directory of this kind left by a process
// that has ended? (OutputDir::removeStaleOutputs removes those.)
bool isStalePrivateDirName(const std::string& name);

}  // namespace metrosync
