#include "tools/cli/sweep_mpi.h"

#include <mpi.h>
#include <sched.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <exception>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>

#include "sim/parallel/worker_pool.h"
#include "tools/cli/basin.h"
#include "tools/cli/commands.h"
#include "tools/cli/fault_hooks.h"
#include "tools/cli/sweep_messages.h"
#include "tools/report/outputs.h"

namespace metrosync::cli {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTagStart = 1, kTagReport = 2, kTagWork = 3;
// How often a process waiting for a message looks for one (sleeping in between, not spinning on
// a core that a point could use).
constexpr auto kPollInterval = std::chrono::milliseconds(1);
// After a stop request, how long rank 0 waits for the workers' last reports before it gives up
// on them (mpirun normally ends them within a few seconds).
constexpr auto kStopGrace = std::chrono::seconds(10);
// A worker keeps up to this many points per thread queued or running (the rest of the grid stays
// with rank 0 for whoever asks first).
constexpr long kPointsInFlightPerThread = 2;

void sendBytes(const std::string& bytes, int dest, int tag) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD);
}

// A waiting message with `tag` from `source` (MPI_ANY_SOURCE: any), received; nullopt if none.
std::optional<std::string> tryReceive(int source, int tag, int* from = nullptr) {
  int flag = 0;
  MPI_Status st;
  MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &st);
  if (!flag) return std::nullopt;
  int n = 0;
  MPI_Get_count(&st, MPI_BYTE, &n);
  std::string bytes(static_cast<size_t>(n), '\0');
  MPI_Recv(bytes.data(), n, MPI_BYTE, st.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  if (from) *from = st.MPI_SOURCE;
  return bytes;
}

std::string receive(int source, int tag) {
  for (;;) {
    if (auto bytes = tryReceive(source, tag)) return *bytes;
    std::this_thread::sleep_for(kPollInterval);
  }
}

int worldRank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

// The cores this process may run on: mpirun binds each rank to one core by default (with 2 or
// fewer ranks), srun to its task's CPUs.
int coresAllowed() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) != 0) return 0;
  return CPU_COUNT(&set);
}

// `opt` with --jobs defaulting to the cores this rank may use (not all the node's); a warning when
// more threads are asked for than it may use.
SweepOptions withRankJobs(SweepOptions opt) {
  const int cores = coresAllowed();
  if (opt.jobs <= 0) opt.jobs = std::max(1, cores);
  if (cores > 0 && opt.jobs > cores)
    std::cerr << "metrosync: warning: rank " << worldRank() << " runs --jobs " << opt.jobs
              << " threads on " << cores << (cores == 1 ? " core" : " cores")
              << " (its CPU binding); start it with `mpirun --bind-to none` or `srun "
                 "--cpus-per-task="
              << opt.jobs << "` (docs/cluster.md)\n";
  return opt;
}

// ---- rank 0 -----------------------------------------------------------------------------------

// The grid indices not handed out yet: those given back first, then the wanted ones ascending.
class Dispenser {
 public:
  Dispenser(long size, const std::function<bool(long)>& wanted) : size_(size), wanted_(wanted) {}

  std::vector<long> take(long k) {
    std::lock_guard<std::mutex> l(m_);
    std::vector<long> out;
    while (static_cast<long>(out.size()) < k && !back_.empty()) {
      out.push_back(back_.back());
      back_.pop_back();
    }
    for (; static_cast<long>(out.size()) < k && next_ < size_; ++next_)
      if (wanted_(next_)) out.push_back(next_);
    return out;
  }

  void giveBack(const std::vector<long>& indices) {
    std::lock_guard<std::mutex> l(m_);
    back_.insert(back_.end(), indices.rbegin(), indices.rend());
  }

  bool exhausted() {
    std::lock_guard<std::mutex> l(m_);
    while (next_ < size_ && !wanted_(next_)) ++next_;
    return back_.empty() && next_ >= size_;
  }

 private:
  std::mutex m_;
  long size_, next_ = 0;
  const std::function<bool(long)>& wanted_;
  std::vector<long> back_;
};

// Hands finished points to the sweep's sink one at a time, from any thread; the first exception
// ends the handing out of points.
class Delivery {
 public:
  explicit Delivery(const SweepPointSink& sink) : sink_(sink) {}
  void deliver(const SweepPoint& p) {
    std::lock_guard<std::mutex> l(m_);
    if (error_) return;
    try {
      sink_(p);
    } catch (...) {
      error_ = std::current_exception();
    }
  }
  void fail(std::exception_ptr e) {
    std::lock_guard<std::mutex> l(m_);
    if (!error_) error_ = e;
  }
  bool failed() {
    std::lock_guard<std::mutex> l(m_);
    return error_ != nullptr;
  }
  void rethrow() {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::mutex m_;
  const SweepPointSink& sink_;
  std::exception_ptr error_;
};

class Coordinator {
 public:
  explicit Coordinator(int ranks) : workers_(ranks - 1) {}

  // The SweepScheduler: rank 0's threads and the workers take points from one dispenser.
  // Returns how many local threads ran points (the pool of sim/parallel/worker_pool.h: those
  // the system refused to start are left out; with none, the workers run every point).
  int schedule(long size, const std::function<bool(long)>& wanted, int jobs,
               const SweepPointRunner& run, const SweepPointSink& finished,
               const std::function<bool()>& stop) {
    started_ = true;
    for (int w = 1; w <= workers_; ++w) sendBytes("start", w, kTagStart);
    Dispenser points(size, wanted);
    Delivery delivery(finished);
    WorkerThreads local(workerCount(jobs, size), [&] { runLocally(points, delivery, run, stop); });
    try {
      serveWorkers(points, delivery, stop);
      served_ = true;
    } catch (...) {  // the local threads stop too; the workers are left to MPI_Abort
      delivery.fail(std::current_exception());
    }
    local.join();
    delivery.rethrow();
    return local.started();
  }

  // Workers that were never started are told to quit.
  void release() {
    if (!started_ && !released_)
      for (int w = 1; w <= workers_; ++w) sendBytes("quit", w, kTagStart);
    released_ = true;
  }

  // Started workers that are still running (rank 0 left the scheduler by an exception, or gave
  // up on silent workers after a stop request): only MPI_Abort ends them.
  bool workersLeft() const { return (started_ && !served_) || abandoned_; }

 private:
  static void runLocally(Dispenser& points, Delivery& delivery, const SweepPointRunner& run,
                         const std::function<bool()>& stop) {
    for (;;) {
      if (delivery.failed() || stop()) return;
      const std::vector<long> g = points.take(1);
      if (g.empty()) return;
      std::optional<SweepPoint> p;
      try {
        p = run(g[0]);
      } catch (...) {
        delivery.fail(std::current_exception());
        return;
      }
      if (p) delivery.deliver(*p);
    }
  }

  // Answers every report until each worker has sent its last one (or, after a stop request,
  // until kStopGrace has passed in silence).
  void serveWorkers(Dispenser& points, Delivery& delivery, const std::function<bool()>& stop) {
    int active = workers_;
    std::optional<Clock::time_point> silent_since;
    while (active > 0) {
      int from = 0;
      const std::optional<std::string> bytes = tryReceive(MPI_ANY_SOURCE, kTagReport, &from);
      if (!bytes) {
        if (stop() && !silent_since) silent_since = Clock::now();
        if (silent_since && Clock::now() - *silent_since > kStopGrace) {
          abandoned_ = true;
          return;
        }
        std::this_thread::sleep_for(kPollInterval);
        continue;
      }
      silent_since.reset();
      const SweepReport report = decodeReport(*bytes);
      for (const SweepPoint& p : report.points) delivery.deliver(p);
      points.giveBack(report.unrun);
      if (report.done) {
        --active;
        continue;
      }
      SweepWork work;
      const bool halt = stop() || delivery.failed();
      if (!halt) work.indices = points.take(report.want);
      work.last = halt || points.exhausted();
      sendBytes(encodeWork(work), from, kTagWork);
    }
  }

  int workers_;
  bool started_ = false, released_ = false, served_ = false, abandoned_ = false;
};

// ---- a worker rank ----------------------------------------------------------------------------

// What a worker's threads share with its main thread (the only one that calls MPI).
struct WorkerQueue {
  std::mutex m;
  std::condition_variable cv;
  std::deque<long> todo;
  std::vector<SweepPoint> finished;
  std::vector<long> unrun;
  long running = 0;
  bool last = false;
};

void computeThread(WorkerQueue& q, const SweepPointRunner& run, long& ran) {
  for (;;) {
    long g = 0;
    {
      std::unique_lock<std::mutex> l(q.m);
      q.cv.wait(l, [&] { return !q.todo.empty() || q.last; });
      if (q.todo.empty()) return;
      g = q.todo.front();
      q.todo.pop_front();
      ++q.running;
    }
    const std::optional<SweepPoint> p = run(g);
    {
      std::lock_guard<std::mutex> l(q.m);
      --q.running;
      if (p)
        q.finished.push_back(*p);
      else
        q.unrun.push_back(g);  // interrupted by a stop request
      ++ran;  // a test's fault hook may end the rank here (tools/cli/fault_hooks.h)
      if (faultHooks().after_worker_point) faultHooks().after_worker_point(worldRank(), ran);
    }
    q.cv.notify_all();
  }
}

// The next report: what finished, what will not run, how many more points fit.
SweepReport nextReport(WorkerQueue& q, long threads) {
  std::unique_lock<std::mutex> l(q.m);
  const auto worth_sending = [&] {
    return !q.finished.empty() || (!q.last && static_cast<long>(q.todo.size()) < threads) ||
           (q.last && q.todo.empty() && q.running == 0) || FileSink::stopRequested();
  };
  q.cv.wait_for(l, std::chrono::milliseconds(200), worth_sending);
  if (FileSink::stopRequested() && !q.last) {  // give back what has not started
    q.unrun.insert(q.unrun.end(), q.todo.begin(), q.todo.end());
    q.todo.clear();
    q.last = true;
    q.cv.notify_all();
  }
  SweepReport r;
  r.done = q.last && q.todo.empty() && q.running == 0;
  r.points.swap(q.finished);
  r.unrun.swap(q.unrun);
  r.want = q.last ? 0
                  : std::max(0L, kPointsInFlightPerThread * threads -
                                     static_cast<long>(q.todo.size()) - q.running);
  return r;
}

void workerLoop(const SweepPointRunner& run, int threads) {
  WorkerQueue q;
  long ran = 0;
  WorkerThreads pool(threads, [&] { computeThread(q, run, ran); });
  if (pool.started() == 0)
    throw std::runtime_error("rank " + std::to_string(worldRank()) +
                             ": no worker thread could start (the process limit on threads)");
  threads = pool.started();
  for (;;) {
    const SweepReport report = nextReport(q, threads);
    if (!report.done && report.points.empty() && report.unrun.empty() && report.want == 0) continue;
    sendBytes(encodeReport(report), 0, kTagReport);
    if (report.done) break;
    const SweepWork work = decodeWork(receive(0, kTagWork));
    {
      std::lock_guard<std::mutex> l(q.m);
      q.todo.insert(q.todo.end(), work.indices.begin(), work.indices.end());
      q.last = q.last || work.last;
    }
    q.cv.notify_all();
  }
  pool.join();
}

}  // namespace

namespace {

// Rank 0 of `ranks`: `command` runs with its points scheduled over the ranks; every worker rank is
// released (quit, or its `done` awaited) before this returns.
int coordinate(int ranks, const std::function<int(const SweepScheduler&)>& command) {
  Coordinator c(ranks);
  const SweepScheduler schedule = [&c](long size, const std::function<bool(long)>& wanted, int jobs,
                                       const SweepPointRunner& run, const SweepPointSink& finished,
                                       const std::function<bool()>& stop) {
    return c.schedule(size, wanted, jobs, run, finished, stop);
  };
  int code = 0;
  try {
    code = command(schedule);
  } catch (const std::exception& e) {
    c.release();
    if (!c.workersLeft()) throw;
    std::cerr << "metrosync: error: " << e.what() << "\n";
    code = kOtherError;
  }
  c.release();
  if (c.workersLeft()) {
    std::cerr << "metrosync: error: ending the worker ranks still running (continue with "
                 "--resume)\n";
    MPI_Abort(MPI_COMM_WORLD, code != kSuccess ? code : kOtherError);
  }
  return code;
}

// A worker rank: waits for rank 0's start, then runs the points it is given with `runner()`'s
// runner on `jobs` threads.
int work(int jobs, const std::function<SweepPointRunner()>& runner) {
  if (receive(0, kTagStart) != "start") return kSuccess;  // rank 0 ended before running points
  SweepPointRunner run;
  try {
    run = runner();  // rank 0's checks passed: a failure here is this node's
  } catch (const std::exception& e) {
    std::cerr << "metrosync: error: rank " << worldRank() << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, kBadInput);
  }
  installStopHandlers();
  try {
    workerLoop(run, std::max(1, jobs));
  } catch (const std::exception& e) {  // rank 0 would wait for this rank forever
    std::cerr << "metrosync: error: rank " << worldRank() << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, kOtherError);
  }
  return kSuccess;
}

}  // namespace

int mpiSweepCoordinator(const SweepOptions& options, int ranks) {
  const SweepOptions opt = withRankJobs(options);
  return coordinate(ranks, [&](const SweepScheduler& schedule) {
    // the points' envelope rows stay on the rank that ran them (sweep_messages.h carries none)
    if (!opt.keep.empty())
      throw UsageError("--keep " + opt.keep +
                       ": not available under MPI; keep the envelopes per shard (--shard K/N, "
                       "docs/cluster.md) or run without MPI");
    return sweepCommand(opt, schedule, ranks);
  });
}

int mpiSweepWorker(const SweepOptions& options) {
  const SweepOptions opt = withRankJobs(options);
  return work(opt.jobs, [&] { return sweepPointRunner(opt); });
}

int mpiBasinCoordinator(const BasinOptions& options, int ranks) {
  BasinOptions opt = options;
  opt.run = withRankJobs(options.run);
  return coordinate(
      ranks, [&](const SweepScheduler& schedule) { return basinCommand(opt, schedule, ranks); });
}

int mpiBasinWorker(const BasinOptions& options) {
  BasinOptions opt = options;
  opt.run = withRankJobs(options.run);
  return work(opt.run.jobs, [&] { return basinSampleRunner(opt); });
}

}  // namespace metrosync::cli
