#include "sim/record/private_dir.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace metrosync {

namespace {

const std::string kPrefix = ".metrosync-tmp.";

std::runtime_error failure(const std::string& what, const std::string& path) {
  return std::runtime_error("cannot " + what + " " + path + ": " + std::strerror(errno));
}

}  // namespace

PrivateDir::PrivateDir(const std::string& parent) {
  std::string pattern = parent + "/" + kPrefix + std::to_string(::getpid()) + ".XXXXXX";
  if (::mkdtemp(pattern.data()) == nullptr) throw failure("make a private folder in", parent);
  path_ = pattern;
  fd_ = ::open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  struct stat st {};
  if (fd_ < 0 || ::fstat(fd_, &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid() ||
      (st.st_mode & 0777) != 0700) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw std::runtime_error(path_ + " is not the private folder metrosync just made (replaced?)");
  }
}

PrivateDir::~PrivateDir() {
  if (fd_ < 0) return;
  // every file in it: those made here and those the child program made
  const int list_fd = ::dup(fd_);
  if (DIR* d = list_fd >= 0 ? ::fdopendir(list_fd) : nullptr) {
    std::vector<std::string> names;
    while (const dirent* e = ::readdir(d))
      if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0)
        names.emplace_back(e->d_name);
    ::closedir(d);
    for (const auto& n : names) ::unlinkat(fd_, n.c_str(), 0);
  } else if (list_fd >= 0) {
    ::close(list_fd);
  }
  ::close(fd_);
  ::rmdir(path_.c_str());  // only ever removes an empty folder
}

int PrivateDir::createOpen(const std::string& name) {
  const int fd =
      ::openat(fd_, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) throw failure("write", path_ + "/" + name);
  return fd;
}

void PrivateDir::create(const std::string& name, const std::string& contents) {
  const int fd = createOpen(name);
  size_t done = 0;
  while (done < contents.size()) {
    const ssize_t w = ::write(fd, contents.data() + done, contents.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      const std::runtime_error e = failure("write", path_ + "/" + name);
      ::close(fd);
      throw e;
    }
    done += static_cast<size_t>(w);
  }
  ::close(fd);
}

int PrivateDir::openForWriting(const std::string& name) const {
  return ::openat(fd_, name.c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
}

int PrivateDir::openForReading(const std::string& name) const {
  return ::openat(fd_, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
}

std::string PrivateDir::read(const std::string& name) const {
  const int fd = openForReading(name);
  if (fd < 0) return "";
  std::string text;
  char buf[1 << 14];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buf, static_cast<size_t>(n));
  }
  ::close(fd);
  return text;
}

long long PrivateDir::size(const std::string& name) const {
  struct stat st {};
  if (::fstatat(fd_, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode))
    return -1;
  return static_cast<long long>(st.st_size);
}

bool PrivateDir::publish(const std::string& name, const std::string& final_path) {
  return ::renameat(fd_, name.c_str(), AT_FDCWD, final_path.c_str()) == 0;
}

std::string PrivateDir::childPath(const std::string& name) {
  return "/proc/self/fd/" + std::to_string(kChildDirFd) + "/" + name;
}

bool isStalePrivateDirName(const std::string& name) {
  if (name.compare(0, kPrefix.size(), kPrefix) != 0) return false;
  const std::string rest = name.substr(kPrefix.size());  // <pid>.XXXXXX
  const size_t dot = rest.find('.');
  const std::string pid_text = rest.substr(0, dot);
  if (dot == std::string::npos || pid_text.empty() ||
      pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9)
    return false;
  const long pid = std::stol(pid_text);
  return pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

}  // namespace metrosync
