// Durable output files, written whole or not at all: every file goes to a hidden temporary name
// in its directory (".NAME.<pid>.part") and is renamed to NAME when complete, so an interrupted
// run never leaves a truncated file that looks complete. Rows stream to the temporary file as
// they go (flushed about once a second): memory does not grow with the length of a run.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace metrosync {

// The metrosync version written to summary.json (the CMake project version when the build
// defines METROSYNC_VERSION).
const char* metrosyncVersion();

// One output file. Rows are appended to the temporary file; commit() renames it to its final
// name; destroyed (or discarded) without commit, the temporary file is removed.
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
  // flush, sync, close and rename; throws std::runtime_error on an I/O error (the temporary
  // file is then removed)
  void commit();
  void discard();

  const std::string& finalPath() const { return final_path_; }
  const std::string& tempPath() const { return temp_path_; }
  bool open() const { return file_ != nullptr; }

 private:
  std::string final_path_, temp_path_;
  std::FILE* file_ = nullptr;
  std::chrono::steady_clock::time_point last_flush_;
};

// The temporary name of `final_path` (".NAME.<pid>.part" in the same directory), for files that
// another program writes (plots).
std::string temporaryPathFor(const std::string& final_path);

// Writes `contents` to `path` through an AtomicFile.
void writeFileAtomically(const std::string& path, const std::string& contents);

}  // namespace metrosync
