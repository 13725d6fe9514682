// The CPU time of the calling thread (a sweep's points and a bench's records run on several
// threads at once: each is timed on its own thread).
#pragma once

namespace metrosync {

// CPU seconds the calling thread has used (CLOCK_THREAD_CPUTIME_ID).
double threadCpuSeconds();

}  // namespace metrosync
