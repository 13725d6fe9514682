// Durable output files, written whole or not at all: every file goes to a hidden temporary name
// in its directory (".NAME.<pid>.part") and is renamed to NAME when complete, so an interrupted
// run never leaves a truncated file that looks complete. Rows stream to the temporary file as
// they go (flushed about once a second): memory does not grow with the length of a run.
#pragma once

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "sim/record/finite_check.h"

namespace metrosync {

// The metrosync version written to summary.json (the CMake project version when the build
// defines METROSYNC_VERSION).
const char* metrosyncVersion();

// One output file. Rows are appended to the temporary file; commit() renames it to its final
// name; destroyed (or discarded) without commit, the temporary file is removed. A CSV file (a
// final name ending in ".csv") has every row checked as it is written (CsvCheck,
// sim/record/finite_check.h): a non-finite number throws NonFiniteOutput and nothing of it
// reaches the file.
class AtomicFile {
 public:
  // Opens the temporary file next to `final_path`; throws std::runtime_error when it cannot.
  explicit AtomicFile(std::string final_path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(const std::string& text);
  // text + '\n'; flushes to disk about once a second, so a long run shows progress on disk
  void writeLine(const std::string& line);
  // lines already ending in '\n' (a block of rows at once); flushes as writeLine does
  void writeLines(const std::string& lines);
  // `rows` such lines whose writer has checked every cell itself (finite numbers and words that
  // cannot spell one: tools/report/deferred_rows.h): counted by the CSV check, not read again
  void writeCheckedLines(const std::string& lines, long rows);
  // flush, sync, close and rename (inside a CommitBatch: flush, close and queue); throws
  // std::runtime_error on an I/O error (the temporary file is then removed)
  void commit();
  void discard();

  const std::string& finalPath() const { return final_path_; }
  const std::string& tempPath() const { return temp_path_; }
  bool open() const { return file_ != nullptr; }

 private:
  void put(const std::string& text);

  std::string final_path_, temp_path_;
  void flushNowAndThen();

  std::FILE* file_ = nullptr;
  std::chrono::steady_clock::time_point last_flush_;
  std::unique_ptr<CsvCheck> check_;  // a CSV file's rows
};

// One sync for the output files of a run instead of one per file (docs/bench/process.md). While
// a CommitBatch is alive, AtomicFile::commit() on the same thread flushes and closes the
// temporary file, starts its write-back (sync_file_range) and queues it, renaming nothing;
// finish() then waits for all the data at once (the files' fsyncs run concurrently, so that they
// share the device's cache flushes), renames the files in the order they were committed, and
// fsyncs each of their directories once. A crash at any point leaves every file either absent or
// old and complete, or new and complete, as with single commits. Code that reads a committed file
// back by its final name before finish() must not run inside a batch. Destroyed without finish()
// (an exception), the batch removes the queued temporary files: nothing of it is written.
class CommitBatch {
 public:
  CommitBatch();
  CommitBatch(const CommitBatch&) = delete;
  CommitBatch& operator=(const CommitBatch&) = delete;
  ~CommitBatch();

  // Syncs, renames and syncs the directories; throws std::runtime_error on an I/O error (the
  // temporary files not yet renamed are then removed). The batch is then no longer current.
  void finish();
  bool active() const { return active_; }  // not yet finished (nor destroyed)

  // The batch AtomicFile::commit() queues into on this thread (nullptr: none).
  static CommitBatch* current();
  void add(const std::string& temp_path, const std::string& final_path);

 private:
  struct Pending {
    std::string temp, final_path;
  };
  std::vector<Pending> pending_;
  CommitBatch* previous_ = nullptr;
  bool active_ = true;
  void release();
  void removeTemporaries(std::size_t from);
};

// The temporary name of `final_path` (".NAME.<pid>.part" in the same directory), for files that
// another program writes (plots).
std::string temporaryPathFor(const std::string& final_path);

// Creates a new temporary file for `final_path` (sim/record/safe_open.h: never through a link or
// over an existing name): ".NAME.<pid>.part", or ".NAME.<k>.<pid>.part" when that name is
// taken. Returns the open descriptor and sets `temp_path`; throws UnsafeFileError when every
// name is taken.
int createTemporaryFor(const std::string& final_path, std::string& temp_path);

// A new temporary file for `final_path` holding `contents`, closed; returns its name. For files
// another program writes or reads (a plot's data, script, log and image): the name is made
// metrosync's own regular file before the program opens it. Throws std::runtime_error.
std::string newTemporaryFile(const std::string& final_path, const std::string& contents = "");

// Writes `contents` to `path` through an AtomicFile.
void writeFileAtomically(const std::string& path, const std::string& contents);

}  // namespace metrosync
