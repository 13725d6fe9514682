// A run's recording on a thread of its own: the run's thread writes records (a few doubles each:
// a step's stages, an event's state) into a block, and a recording thread turns full blocks into
// rows (interpolation, the envelope's quadrature, the sink's calls) while the run integrates on.
// On a machine with a core to spare, recording then costs the run a few stores per record; the
// run waits only when the recording thread falls kMaxQueuedBlocks behind (memory stays bounded
// whatever the run's length) and at its end (drain()).
//
// The records' format is the caller's: `consume` gets each block (records end to end) on the
// recording thread, in the order they were written. What consume throws (a sink's stop request,
// a full disk) stops the recording thread; the run's thread gets it back, the same exception, at
// its next record (rethrowIfFailed, reserve) or at drain().
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace metrosync {

class RecordingThread {
 public:
  using Consume = std::function<void(const double* block, size_t size)>;
  // block_doubles: a block's size, at least the largest record (a larger one is a logic error)
  RecordingThread(Consume consume, size_t block_doubles);
  ~RecordingThread();
  RecordingThread(const RecordingThread&) = delete;
  RecordingThread& operator=(const RecordingThread&) = delete;

  // Room for a record of n doubles at the current block's end (the block is handed over first if
  // the record would not fit); write the record there before the next call. Rethrows what the
  // recording thread threw.
  double* reserve(size_t n) {
    if (failed_.load(std::memory_order_relaxed)) rethrow();
    if (used_ + n > capacity_) post();
    double* at = block_.get() + used_;
    used_ += n;
    return at;
  }
  // Hands every record over and waits until the recording thread has consumed them all; rethrows
  // what it threw.
  void drain();

 private:
  void post();
  void loop();
  void rethrow();

  static constexpr size_t kMaxQueuedBlocks = 8;
  Consume consume_;
  size_t capacity_;
  // a block: capacity_ doubles, not initialized (the records overwrite what they use)
  using Memory = std::unique_ptr<double[]>;
  struct Block {
    Memory data;
    size_t used = 0;
  };
  Memory block_;  // being written by the run's thread, its first used_ doubles
  size_t used_ = 0;
  std::deque<Block> queue_;    // handed over, oldest first
  std::vector<Memory> spare_;  // consumed blocks, their memory reused
  std::mutex mutex_;
  std::condition_variable wake_recorder_, wake_run_;
  bool stop_ = false, busy_ = false;
  std::atomic<bool> failed_{false};
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace metrosync
