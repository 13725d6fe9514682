// Runs another program for the benchmark (the careful peer, `metrosync run`, `metrosync sweep`)
// and measures it from outside: its exit, what it printed, its wall time and its CPU time.
#pragma once

#include <string>
#include <vector>

namespace metrosync::bench {

struct ProcessResult {
  bool started = false;  // false: the program could not be run at all (why in `error`)
  int exit_code = -1;    // the exit status; -1 when it was killed by a signal
  bool timed_out = false;
  std::string out, err;  // everything it wrote on stdout and stderr
  std::string error;     // why it could not be run
  double wall_s = 0.0;   // from just before the start to just after the exit
  // the steady clock's readings (seconds since its epoch; CLOCK_MONOTONIC, as the child's own)
  // just before the start and just after the exit
  double start_s = 0.0, end_s = 0.0;
  double cpu_s = 0.0;  // user + system time of the process and its children (rusage)
  bool ok() const { return started && !timed_out && exit_code == 0; }
};

// Runs argv[0] (a path, or a name looked up on PATH) with argv[1..], stdin from /dev/null, in
// this process's environment and `env` ("NAME=VALUE" each) besides.
// timeout_s > 0: the process is killed (SIGKILL) once it has run that long.
ProcessResult runProcess(const std::vector<std::string>& argv, double timeout_s = 0.0,
                         const std::vector<std::string>& env = {});

// The command line as a shell would take it back (single quotes where needed), for messages and
// for the pages that record how a number was made.
std::string shellCommand(const std::vector<std::string>& argv);

}  // namespace metrosync::bench
