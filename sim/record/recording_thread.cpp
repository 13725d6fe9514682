#include "sim/record/recording_thread.h"

#include <utility>

namespace metrosync {

RecordingThread::RecordingThread(Consume consume, size_t block_doubles)
    : consume_(std::move(consume)), capacity_(block_doubles), block_(new double[block_doubles]) {
  thread_ = std::thread([this] { loop(); });
}

RecordingThread::~RecordingThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  wake_recorder_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void RecordingThread::post() {
  if (used_ == 0) return;
  Memory next;
  std::unique_lock<std::mutex> lock(mutex_);
  wake_run_.wait(lock, [&] { return queue_.size() < kMaxQueuedBlocks || error_; });
  if (error_) {
    lock.unlock();
    rethrow();
  }
  queue_.push_back({std::move(block_), used_});
  if (!spare_.empty()) {
    next = std::move(spare_.back());
    spare_.pop_back();
  }
  lock.unlock();
  wake_recorder_.notify_one();
  block_ = next ? std::move(next) : Memory(new double[capacity_]);
  used_ = 0;
}

void RecordingThread::drain() {
  post();
  std::unique_lock<std::mutex> lock(mutex_);
  wake_run_.wait(lock, [&] { return (queue_.empty() && !busy_) || error_; });
  lock.unlock();
  if (failed_.load()) rethrow();
}

void RecordingThread::rethrow() {
  std::exception_ptr e;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    e = error_;
  }
  if (e) std::rethrow_exception(e);
}

void RecordingThread::loop() {
  for (;;) {
    Block block;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_recorder_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      block = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
    }
    wake_run_.notify_all();  // room in the queue
    std::exception_ptr error;
    try {
      consume_(block.data.get(), block.used);
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      busy_ = false;
      spare_.push_back(std::move(block.data));
      if (error && !error_) {
        error_ = error;
        failed_.store(true);
      }
    }
    wake_run_.notify_all();
    if (error) return;
  }
}

}  // namespace metrosync
