#include "tools/cli/phase_clock.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace metrosync::cli {

namespace {

using Clock = std::chrono::steady_clock;

struct Phases {
  bool on = false;
  bool started = false;
  Clock::time_point last;
};

Phases& phases() {
  static Phases p = [] {
    Phases q;
    const char* v = std::getenv("METROSYNC_PHASES");
    q.on = v && *v && std::strcmp(v, "0") != 0;
    return q;
  }();
  return p;
}

}  // namespace

void markPhase(const char* name) {
  Phases& p = phases();
  if (!p.on) return;
  const Clock::time_point now = Clock::now();
  const double at = std::chrono::duration<double>(now.time_since_epoch()).count();
  if (p.started)
    std::fprintf(stderr, "metrosync: phase %s %.3f ms (at %.9f s)\n", name,
                 1e3 * std::chrono::duration<double>(now - p.last).count(), at);
  else
    std::fprintf(stderr, "metrosync: phase %s at %.9f s\n", name, at);
  p.started = true;
  p.last = now;
}

}  // namespace metrosync::cli
