// Running the built `metrosync` binary from a test (METROSYNC_BINARY, set by CMake): the one
// helper every end-to-end test folder uses.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace metrosync::testing_support {

struct CommandResult {
  int code = -1;  // exit code, or 128 + signal
  std::string out, err;
};

// Single-quoted for the shell.
inline std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A fresh path for one test's scratch directory (removed if it existed; created if `create`).
inline std::string scratchDir(const std::string& prefix, const std::string& name,
                              bool create = false) {
  const std::string d =
      ::testing::TempDir() + "/metrosync_" + prefix + "_" + name + "_" + std::to_string(::getpid());
  std::filesystem::remove_all(d);
  if (create) std::filesystem::create_directories(d);
  return d;
}

struct RunIn {
  std::string cwd;  // run in this directory (created); empty: the current one
  std::string env;  // prefix such as "VAR=value"
};

// Runs the shell command `cmd` with no standard input; captures stdout and stderr.
inline CommandResult runCommand(const std::string& cmd) {
  static int counter = 0;
  const std::string err_path = ::testing::TempDir() + "/metrosync_stderr_" +
                               std::to_string(::getpid()) + "_" + std::to_string(counter++);
  CommandResult r;
  FILE* p = ::popen((cmd + " 2>" + shellQuote(err_path) + " </dev/null").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = slurp(err_path);
  std::remove(err_path.c_str());
  return r;
}

// Does `env` set one of the fault variables of tools/cli/fault_hooks.h? Only the test-only
// builds metrosync-faults and metrosync-mpi-faults read them.
inline bool setsFaults(const std::string& env) {
  for (const char* v :
       {"METROSYNC_SWEEP_FAIL_AT=", "METROSYNC_SWEEP_STOP_AFTER=", "METROSYNC_MPI_KILL_AFTER="})
    if (env.find(v) != std::string::npos) return true;
  return false;
}

// Runs `[env] metrosync ARGS` with no standard input; captures stdout and stderr. With a fault
// variable in `env`, the program is metrosync-faults (the same with the tests' fault hooks).
inline CommandResult runMetrosync(const std::string& args, const RunIn& in = {}) {
  std::string cmd;
  if (!in.cwd.empty()) {
    std::filesystem::create_directories(in.cwd);
    cmd = "cd " + shellQuote(in.cwd) + " && ";
  }
  const char* binary = setsFaults(in.env) ? METROSYNC_FAULTS_BINARY : METROSYNC_BINARY;
  return runCommand(cmd + in.env + " " + shellQuote(binary) + " " + args);
}

// The cells of every line of a CSV file (no quoting: metrosync's own CSVs), the header included.
inline std::vector<std::vector<std::string>> csvRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

// Two identical metronomes of the paper's experiment in scaled variables
// (yaml/rigs/experiment-map.yaml), run to `tau`: DIR/pair.yaml, its path returned.
inline std::string writePairRig(const std::string& dir, double tau) {
  const std::string path = dir + "/pair.yaml";
  std::ofstream(path) << "units: scaled\nname: pair\nepsilon: 0.07319\n"
                         "platform:\n  friction: {law: coulomb, mu: 0.03283}\n"
                         "metronomes:\n"
                         "  - {nu: 0.6544, J: 3.138, theta_c: 0.9019, start: {A: 2.902, phi: 0}}\n"
                         "  - {nu: 0.6544, J: 3.138, theta_c: 0.9019, start: {A: 2.902, phi: 0}}\n"
                         "simulation:\n  tau: "
                      << tau << "\n";
  return path;
}

}  // namespace metrosync::testing_support
