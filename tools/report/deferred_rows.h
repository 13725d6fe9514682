// Rows of numbers formatted and written on a thread of their own: the run's thread copies a row's
// numbers into a block and goes on; a writer thread turns full blocks into text (docs/outputs.md:
// wall_seconds holds the copying, write_seconds what was left to write when the run ended).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace metrosync {

class AtomicFile;

class DeferredRows {
 public:
  // format(row, line): appends one row's text (without the newline) to `line`; called on the
  // writer thread, so it may use only what it captured by value. Returns true when it has checked
  // the row itself: every cell a finite number (tested as a double where it is formatted) or a
  // word that cannot spell one; a block of such rows skips the file's text check (CsvCheck).
  // False: the row goes through the text check, which names a non-finite cell (file, row,
  // column).
  using Format = std::function<bool(const double* row, std::string& line)>;

  DeferredRows(AtomicFile& file, size_t width, Format format);
  DeferredRows(const DeferredRows&) = delete;
  DeferredRows& operator=(const DeferredRows&) = delete;
  ~DeferredRows();  // stops the writer; rows not yet written are dropped (the file is discarded)

  // Copies `width` numbers. Rethrows the writer's first error (a full disk, say).
  void add(const double* row);
  // Writes every row added so far and waits for it; rethrows the writer's first error.
  void finish();
  // From now on a full block is written by the thread that adds it (no writer thread): for rows
  // that come from a recording thread already (RunSink::recordingThreadStarted), or for a
  // bench's variant (RunFilesOptions::text_on_rows_thread). Called before the first add; errors
  // then come straight from add and finish.
  void writeOnCallersThread() { on_callers_thread_ = true; }

 private:
  void flushBlock();
  void post(std::vector<double>&& block);
  void writerLoop();
  void writeBlock(const std::vector<double>& block, std::string& text);
  void rethrow();

  AtomicFile& file_;
  const size_t width_;
  const Format format_;
  std::vector<double> block_;
  std::mutex mutex_;
  std::condition_variable wake_writer_, wake_run_;
  std::deque<std::vector<double>> queue_;
  bool busy_ = false, stop_ = false;
  bool on_callers_thread_ = false;
  std::string text_;  // a block's text, when written on the caller's thread
  std::exception_ptr error_;
  std::thread writer_;
};

}  // namespace metrosync
