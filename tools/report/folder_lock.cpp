#include "tools/report/folder_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "sim/record/safe_open.h"

namespace metrosync {

namespace {

std::string readAll(int fd) {
  std::string text;
  char buf[256];
  ssize_t n;
  if (::lseek(fd, 0, SEEK_SET) != 0) return text;
  while ((n = ::read(fd, buf, sizeof buf)) > 0) text.append(buf, static_cast<size_t>(n));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
  return text;
}

}  // namespace

FolderLock::FolderLock(const std::string& dir, const std::string& command)
    : path_(dir + "/" + kFileName) {
  // never through a link or FIFO planted at the name (UnsafeFileError: exit 2)
  fd_ = openOutputFile(path_, false, false, true);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = readAll(fd_);
    ::close(fd_);
    fd_ = -1;
    throw FolderLockedError(dir + " is in use by another process (" +
                            (holder.empty() ? std::string("unknown") : holder) + ", holding " +
                            path_ + "): wait for it to end, or choose another --out");
  }
  taken_over_ = readAll(fd_);
  const std::string me = "pid " + std::to_string(::getpid()) + ": " + command + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) < 0)
    throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);  // releases the flock
}

}  // namespace metrosync
