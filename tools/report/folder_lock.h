// A lock on an output folder, so that two sweeps never write into one folder at once: an
// exclusive flock(2) on DIR/.metrosync.lock, which holds the holder's pid and command. The kernel
// drops the lock when its process ends however it ends (kill -9 included), so a lock file left by
// a killed process is stale by construction: the next sweep takes it over and says so.
#pragma once

#include <stdexcept>
#include <string>

namespace metrosync {

// The folder is locked by a running process (exit 2: choose another folder or wait).
struct FolderLockedError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class FolderLock {
 public:
  static constexpr const char* kFileName = ".metrosync.lock";

  // Locks `dir` (which must exist) for `command` (e.g. "metrosync sweep"); throws
  // FolderLockedError naming the holder, UnsafeFileError when a link, FIFO or hard-linked file
  // sits at the lock's name (sim/record/safe_open.h), std::runtime_error when the lock file
  // cannot be made.
  FolderLock(const std::string& dir, const std::string& command);
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock();  // removes the lock file, then releases the lock

  // What the lock file said when it was taken over from a process that had ended, else "".
  const std::string& takenOver() const { return taken_over_; }

 private:
  std::string path_;
  int fd_ = -1;
  std::string taken_over_;
};

}  // namespace metrosync
