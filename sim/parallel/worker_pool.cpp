#include "sim/parallel/worker_pool.h"

#include <algorithm>
#include <atomic>
#include <system_error>

namespace metrosync {

int workerCount(int jobs, long tasks) {
  const long wanted = jobs > 0 ? jobs : static_cast<long>(std::thread::hardware_concurrency());
  return static_cast<int>(std::max(1L, std::min(wanted, tasks)));
}

WorkerThreads::WorkerThreads(int count, const std::function<void()>& body) : body_(body) {
  threads_.reserve(static_cast<size_t>(std::max(count, 0)));
  for (int t = 0; t < count; ++t) {
    try {
      threads_.emplace_back([this] {
        try {
          body_();
        } catch (...) {
          record(std::current_exception());
        }
      });
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the ones started do the work
    }
  }
}

WorkerThreads::~WorkerThreads() {
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
}

void WorkerThreads::record(std::exception_ptr e) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!error_) error_ = e;
}

void WorkerThreads::join() {
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
  if (error_) std::rethrow_exception(error_);
}

int runWorkers(int threads, const std::function<void()>& worker) {
  WorkerThreads others(threads - 1, worker);
  std::exception_ptr mine;
  try {
    worker();
  } catch (...) {
    mine = std::current_exception();
  }
  others.join();  // rethrows another thread's first exception
  if (mine) std::rethrow_exception(mine);
  return others.started() + 1;
}

int parallelFor(long count, int jobs, const std::function<void(long)>& task,
                const std::function<bool()>& stop) {
  std::atomic<long> next{0};
  std::atomic<bool> failed{false};
  auto worker = [&] {
    for (long k; !failed && (!stop || !stop()) && (k = next++) < count;) {
      try {
        task(k);
      } catch (...) {
        failed = true;
        throw;
      }
    }
  };
  return runWorkers(workerCount(jobs, count), worker);
}

}  // namespace metrosync
