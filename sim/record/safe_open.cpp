#include "sim/record/safe_open.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace metrosync {

namespace {

// What lies at `path` (not following a link), in words, for a refusal.
std::string kindAt(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "missing";
  if (S_ISLNK(st.st_mode)) return "a symbolic link";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (st.st_nlink > 1) return "a file with " + std::to_string(st.st_nlink) + " hard links";
  return "not a regular file";
}

[[noreturn]] void refuse(const std::string& path) {
  throw UnsafeFileError(path + " is " + kindAt(path) +
                        ": metrosync writes and reads only regular files of its own there, "
                        "never through a link (remove it, or choose another folder)");
}

// The descriptor if it is a regular file with one name, else closes it and refuses.
int checkedRegular(int fd, const std::string& path) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1) {
    ::close(fd);
    refuse(path);
  }
  return fd;
}

// Back to blocking I/O once the descriptor is known to be a regular file.
int blocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

}  // namespace

int createNewFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) {
    if (errno == EEXIST) return -1;
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  }
  return checkedRegular(fd, path);
}

int openOutputFile(const std::string& path, bool truncate, bool append, bool readable) {
  // O_NONBLOCK: a FIFO at the name is not waited on (it is refused below)
  const int flags = (readable ? O_RDWR : O_WRONLY) | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK |
                    (append ? O_APPEND : 0);
  const int fd = ::open(path.c_str(), flags, 0666);
  if (fd < 0) {
    if (errno == ELOOP || errno == ENXIO || errno == EISDIR) refuse(path);
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  }
  checkedRegular(fd, path);
  if (truncate && ::ftruncate(fd, 0) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
  return blocking(fd);
}

int openRegularForReading(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    if (errno == ENOENT) return -1;
    if (errno == ELOOP) refuse(path);
    throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    refuse(path);
  }
  return blocking(fd);
}

std::string readRegularFile(const std::string& path) {
  const int fd = openRegularForReading(path);
  if (fd < 0) return "";
  std::string text;
  char buf[1 << 16];
  ssize_t n;
  while ((n = ::read(fd, buf, sizeof buf)) != 0) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw std::runtime_error("cannot read " + path + ": " + why);
    }
    text.append(buf, static_cast<size_t>(n));
  }
  ::close(fd);
  return text;
}

}  // namespace metrosync
