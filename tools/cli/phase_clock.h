// Where `metrosync run`'s time goes, said on stderr when METROSYNC_PHASES=1 (issue 36; read by
// `metrosync_bench process`). One line as each phase ends:
//   metrosync: phase NAME MS ms (at T s)
// NAME the phase that just ended, MS its length in milliseconds, T the steady clock's reading at
// its end (CLOCK_MONOTONIC: the clock a parent that times the whole process shares, so that it can
// tell the start-up before main and the exit after the last phase). The first mark, "main", ends
// no phase: "metrosync: phase main at T s". Without the variable a mark is one test of a flag.
#pragma once

namespace metrosync::cli {

void markPhase(const char* name);

}  // namespace metrosync::cli
