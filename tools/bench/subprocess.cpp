#include "tools/bench/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

extern char** environ;

namespace metrosync::bench {

namespace {

// How often a process with a time limit is looked at: short against the limits used (seconds).
constexpr auto kPollInterval = std::chrono::milliseconds(2);

// A temporary file that is removed when it goes out of scope.
struct TempFile {
  std::string path;
  int fd = -1;
  TempFile() {
    const char* dir = std::getenv("TMPDIR");
    std::string tmpl = std::string(dir && *dir ? dir : "/tmp") + "/metrosync-bench-XXXXXX";
    fd = ::mkstemp(tmpl.data());
    if (fd >= 0) path = tmpl;
  }
  ~TempFile() {
    if (fd >= 0) ::close(fd);
    if (!path.empty()) ::unlink(path.c_str());
  }
  std::string slurp() const {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
};

double cpuOf(const rusage& ru) {
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

// Waits for pid (killing it after timeout_s > 0); fills the exit, the timeout flag and the CPU.
void waitFor(pid_t pid, double timeout_s, std::chrono::steady_clock::time_point t0,
             ProcessResult& r) {
  int status = 0;
  rusage ru{};
  for (;;) {
    const pid_t got = ::wait4(pid, &status, timeout_s > 0 ? WNOHANG : 0, &ru);
    if (got == pid) break;
    if (got < 0 && errno != EINTR) return;
    if (got == 0) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >
          timeout_s) {
        ::kill(pid, SIGKILL);
        r.timed_out = true;
        timeout_s = 0;  // now wait for it to go
        continue;
      }
      std::this_thread::sleep_for(kPollInterval);
    }
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.cpu_s = cpuOf(ru);
}

}  // namespace

ProcessResult runProcess(const std::vector<std::string>& argv, double timeout_s,
                         const std::vector<std::string>& env) {
  ProcessResult r;
  if (argv.empty()) {
    r.error = "no program given";
    return r;
  }
  TempFile out, err;
  if (out.fd < 0 || err.fd < 0) {
    r.error = std::string("cannot create a temporary file: ") + std::strerror(errno);
    return r;
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, out.fd, 1);
  posix_spawn_file_actions_adddup2(&fa, err.fd, 2);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<char*> envp;  // `env` first: getenv() takes a name's first entry
  for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  for (char** e = environ; *e; ++e) envp.push_back(*e);
  envp.push_back(nullptr);
  pid_t pid = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = ::posix_spawnp(&pid, argv[0].c_str(), &fa, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    r.error = "cannot run " + argv[0] + ": " + std::strerror(rc);
    return r;
  }
  r.started = true;
  waitFor(pid, timeout_s, t0, r);
  const auto t1 = std::chrono::steady_clock::now();
  r.wall_s = std::chrono::duration<double>(t1 - t0).count();
  r.start_s = std::chrono::duration<double>(t0.time_since_epoch()).count();
  r.end_s = std::chrono::duration<double>(t1.time_since_epoch()).count();
  r.out = out.slurp();
  r.err = err.slurp();
  return r;
}

std::string shellCommand(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) {
    const bool plain = !a.empty() && a.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_-+=/.,:@%") == std::string::npos;
    std::string q = a;
    if (!plain) {
      q = "'";
      for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
      q += "'";
    }
    s += (s.empty() ? "" : " ") + q;
  }
  return s;
}

}  // namespace metrosync::bench
