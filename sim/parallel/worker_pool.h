// The one pool of worker threads of metrosync (issues 24 and 29): sweeps, basins, validation, the
// paper's figures and the output files' syncs all run their work through it. It never starts
// more threads than there is work, and a thread the system refuses to start (the process or user
// limit on threads, EAGAIN) is not an abort: the work runs on the threads that did start, the
// calling thread always among them.
#pragma once

#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace metrosync {

// Threads for `tasks` pieces of work asked to run on `jobs` threads: min(jobs, tasks), at least
// 1; jobs <= 0 means the machine's cores.
int workerCount(int jobs, long tasks);

// Up to `count` threads running `body`, started at construction and joined by join() or the
// destructor. A thread the system cannot start is left out, with every one after it.
class WorkerThreads {
 public:
  WorkerThreads(int count, const std::function<void()>& body);
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;
  ~WorkerThreads();

  int started() const { return static_cast<int>(threads_.size()); }
  // Waits for every thread; rethrows the first exception a body threw.
  void join();

 private:
  void record(std::exception_ptr e);
  std::function<void()> body_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::exception_ptr error_;
};

// Runs `worker` on `threads` threads, the calling thread one of them, and returns how many ran
// it (1 when no other thread could start). The first exception thrown is rethrown once all are
// done.
int runWorkers(int threads, const std::function<void()>& worker);

// task(k) for every k in [0, count) on up to `jobs` threads, each taking the next k when free;
// after the first exception no new k starts, and it is rethrown at the end. `stop` (optional),
// asked before each k, ends the loop early. Returns the number of threads that ran.
int parallelFor(long count, int jobs, const std::function<void(long)>& task,
                const std::function<bool()>& stop = {});

}  // namespace metrosync
