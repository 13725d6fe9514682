#include "sim/parallel/ordered_tasks.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <vector>

#include "sim/parallel/worker_pool.h"

namespace metrosync {

namespace {

enum class Step { Waiting, Running, Done, Skipped };

// The loop's shared state; every member is guarded by `mutex` (compute runs outside it).
struct Loop {
  Loop(long n, const std::function<bool(long)>& s, const std::function<void(long)>& c,
       const std::function<void(long)>& m)
      : count(n), skip(s), compute(c), commit(m), steps(n, Step::Waiting), errors(n) {}

  long count = 0;
  const std::function<bool(long)>& skip;
  const std::function<void(long)>& compute;
  const std::function<void(long)>& commit;
  std::vector<Step> steps;
  std::vector<std::exception_ptr> errors;  // of compute(k)
  long next = 0;                           // the first k not yet committed or skipped
  std::exception_ptr failed;               // what stops the loop
  std::mutex mutex;
  std::condition_variable changed;

  // Commits (or skips) every k from `next` on whose turn can be decided now.
  void advance() {
    while (next < count && !failed) {
      if (steps[next] != Step::Skipped && skip(next)) steps[next] = Step::Skipped;
      if (steps[next] == Step::Skipped) {
        ++next;
        continue;
      }
      if (steps[next] != Step::Done) return;  // still to compute, or computing
      if (errors[next]) {
        failed = errors[next];
        return;
      }
      try {
        commit(next);
      } catch (...) {
        failed = std::current_exception();
        return;
      }
      ++next;
    }
  }

  // The first k from `next` on still to compute and not skipped; -1 when there is none.
  long pick() {
    for (long k = next; k < count; ++k) {
      if (steps[k] != Step::Waiting) continue;
      if (!skip(k)) return k;
      steps[k] = Step::Skipped;
    }
    return -1;
  }

  void work() {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      advance();
      if (failed || next == count) {
        changed.notify_all();
        return;
      }
      const long k = pick();
      if (k < 0) {
        changed.wait(lock);  // a computing k decides what comes next
        continue;
      }
      steps[k] = Step::Running;
      lock.unlock();
      std::exception_ptr error;
      try {
        compute(k);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      errors[k] = error;
      steps[k] = Step::Done;
      changed.notify_all();
    }
  }
};

}  // namespace

void orderedTasks(long count, int jobs, const std::function<bool(long)>& skip,
                  const std::function<void(long)>& compute,
                  const std::function<void(long)>& commit) {
  if (count <= 0) return;
  Loop loop(count, skip, compute, commit);
  runWorkers(workerCount(jobs, count), [&loop] { loop.work(); });
  if (loop.failed) std::rethrow_exception(loop.failed);
}

}  // namespace metrosync
