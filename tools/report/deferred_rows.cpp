#include "tools/report/deferred_rows.h"

#include "sim/record/atomic_file.h"

namespace metrosync {

namespace {
// Rows per block: large enough that handing a block over (a lock, a wake-up) costs nothing per
// row, small enough that a short run's rows still overlap with its integration.
constexpr size_t kRowsPerBlock = 256;
// Blocks waiting at most: bounds the memory of a run whose rows come faster than the disk takes
// them (the run's thread then waits), whatever the run's length.
constexpr size_t kMaxQueuedBlocks = 8;
}  // namespace

DeferredRows::DeferredRows(AtomicFile& file, size_t width, Format format)
    : file_(file), width_(width), format_(std::move(format)) {
  block_.reserve(width_ * kRowsPerBlock);
}

DeferredRows::~DeferredRows() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  wake_writer_.notify_all();
  if (writer_.joinable()) writer_.join();
}

void DeferredRows::add(const double* row) {
  block_.insert(block_.end(), row, row + width_);
  if (block_.size() == width_ * kRowsPerBlock) flushBlock();
}

// The block so far: written here, its memory reused (on the caller's thread), or handed to the
// writer thread.
void DeferredRows::flushBlock() {
  if (on_callers_thread_) {
    writeBlock(block_, text_);
    block_.clear();
    return;
  }
  std::vector<double> full;
  full.reserve(width_ * kRowsPerBlock);
  full.swap(block_);
  post(std::move(full));
}

void DeferredRows::post(std::vector<double>&& block) {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_run_.wait(lock, [&] { return queue_.size() < kMaxQueuedBlocks || error_; });
  if (error_) {
    lock.unlock();
    rethrow();
  }
  queue_.push_back(std::move(block));
  if (!writer_.joinable()) writer_ = std::thread([this] { writerLoop(); });
  lock.unlock();
  wake_writer_.notify_one();
}

void DeferredRows::finish() {
  if (!block_.empty()) flushBlock();
  std::unique_lock<std::mutex> lock(mutex_);
  wake_run_.wait(lock, [&] { return (queue_.empty() && !busy_) || error_; });
  lock.unlock();
  rethrow();
}

void DeferredRows::rethrow() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

void DeferredRows::writerLoop() {
  std::string text;
  for (;;) {
    std::vector<double> block;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_writer_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      block = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
    }
    wake_run_.notify_all();  // room in the queue
    std::exception_ptr error;
    try {
      writeBlock(block, text);
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      busy_ = false;
      if (error && !error_) error_ = error;
    }
    wake_run_.notify_all();
    if (error) return;
  }
}

void DeferredRows::writeBlock(const std::vector<double>& block, std::string& text) {
  text.clear();
  bool checked = true;
  long rows = 0;
  for (size_t k = 0; k + width_ <= block.size(); k += width_, ++rows) {
    checked = format_(block.data() + k, text) && checked;
    text += '\n';
  }
  // a row with a non-finite number (or one its format did not check): the whole block through
  // the text check, which refuses it by file, row and column before any of it is written
  if (checked)
    file_.writeCheckedLines(text, rows);
  else
    file_.writeLines(text);
}

}  // namespace metrosync
