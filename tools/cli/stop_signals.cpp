#include "tools/cli/stop_signals.h"

#include <signal.h>
#include <unistd.h>

#include "tools/report/outputs.h"

namespace metrosync::cli {

namespace {

extern "C" void onStopSignal(int) {
  FileSink::requestStop();
  static const char msg[] =
      "\nmetrosync: stopping, keeping the files written so far (again to kill)\n";
  ssize_t ignored = ::write(2, msg, sizeof msg - 1);
  (void)ignored;
}

}  // namespace

void installStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a second signal takes the default action
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace metrosync::cli
