#include "sim/record/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "sim/parallel/worker_pool.h"
#include "sim/record/safe_open.h"

namespace metrosync {

#ifndef METROSYNC_VERSION
#define METROSYNC_VERSION "0.1.0"
#endif

const char* metrosyncVersion() {
  return METROSYNC_VERSION;
}

namespace fs = std::filesystem;

namespace {

std::string errnoText() {
  return std::strerror(errno);
}

thread_local CommitBatch* t_batch = nullptr;

// fsync of a closed file by its name (a read-only descriptor syncs the file's data and inode)
bool syncPath(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), O_RDONLY | flags);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

// ".NAME.<pid>.part" next to NAME: hidden, and plainly not a finished output.
std::string temporaryPathFor(const std::string& final_path) {
  const fs::path p(final_path);
  const std::string name = "." + p.filename().string() + "." + std::to_string(::getpid()) + ".part";
  return (p.parent_path() / name).string();
}

// A name already taken (a planted link, a file another process left) is never written through:
// the next name ".NAME.<k>.<pid>.part" is tried instead, up to this many.
constexpr int kTemporaryNameTries = 64;

int createTemporaryFor(const std::string& final_path, std::string& temp_path) {
  const std::string first = temporaryPathFor(final_path);
  const std::string stem = first.substr(0, first.size() - 5);  // without ".part"
  const std::string pid = std::to_string(::getpid());
  for (int k = 0; k < kTemporaryNameTries; ++k) {
    // ".NAME.<pid>.part", then ".NAME.<k>.<pid>.part": the pid stays the last number
    temp_path =
        k == 0 ? first
               : stem.substr(0, stem.size() - pid.size()) + std::to_string(k) + "." + pid + ".part";
    const int fd = createNewFile(temp_path);
    if (fd >= 0) return fd;
  }
  throw UnsafeFileError("cannot write " + final_path + ": its temporary names (" + first + " and " +
                        std::to_string(kTemporaryNameTries - 1) +
                        " more) are all taken by other files; remove them");
}

std::string newTemporaryFile(const std::string& final_path, const std::string& contents) {
  std::string temp_path;
  const int fd = createTemporaryFor(final_path, temp_path);
  size_t done = 0;
  while (done < contents.size()) {
    const ssize_t w = ::write(fd, contents.data() + done, contents.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      const std::string why = errnoText();
      ::close(fd);
      std::remove(temp_path.c_str());
      throw std::runtime_error("cannot write " + temp_path + ": " + why);
    }
    done += static_cast<size_t>(w);
  }
  ::close(fd);
  return temp_path;
}

// ---------------------------------------------------------------------------------------------
// AtomicFile

AtomicFile::AtomicFile(std::string final_path) : final_path_(std::move(final_path)) {
  const int fd = createTemporaryFor(final_path_, temp_path_);
  file_ = ::fdopen(fd, "w");
  if (!file_) {
    const std::string why = errnoText();
    ::close(fd);
    std::remove(temp_path_.c_str());
    throw std::runtime_error("cannot write " + temp_path_ + ": " + why);
  }
  // a large buffer: rows are small and many
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 16);
  last_flush_ = std::chrono::steady_clock::now();
  const std::string name = fs::path(final_path_).filename().string();
  if (name.size() > 4 && name.compare(name.size() - 4, 4, ".csv") == 0)
    check_ = std::make_unique<CsvCheck>(final_path_);
}

AtomicFile::~AtomicFile() {
  discard();
}

void AtomicFile::put(const std::string& text) {
  if (!file_) throw std::logic_error("write to a closed file " + final_path_);
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw std::runtime_error("cannot write " + temp_path_ + ": " + errnoText());
}

void AtomicFile::write(const std::string& text) {
  if (check_) check_->text(text);
  put(text);
}

void AtomicFile::writeLine(const std::string& line) {
  if (check_) check_->line(line);
  put(line);
  if (std::fputc('\n', file_) == EOF)
    throw std::runtime_error("cannot write " + temp_path_ + ": " + errnoText());
  flushNowAndThen();
}

void AtomicFile::writeLines(const std::string& lines) {
  write(lines);  // each whole line checked (CsvCheck::text)
  flushNowAndThen();
}

void AtomicFile::writeCheckedLines(const std::string& lines, long rows) {
  if (check_) check_->passed(rows);
  put(lines);
  flushNowAndThen();
}

// flush about once a second (the clock costs far less than formatting the lines)
void AtomicFile::flushNowAndThen() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ >= std::chrono::seconds(1)) {
    if (std::fflush(file_) != 0)
      throw std::runtime_error("cannot write " + temp_path_ + ": " + errnoText());
    last_flush_ = now;
  }
}

void AtomicFile::commit() {
  if (!file_) throw std::logic_error("commit of a closed file " + final_path_);
  std::FILE* f = file_;
  file_ = nullptr;
  if (CommitBatch* batch = CommitBatch::current()) {
    // flushed, closed and its write-back started; the batch syncs and renames it
    const int fd = ::fileno(f);
    const bool ok = std::fflush(f) == 0 &&
                    (::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE) == 0 || errno == ENOSYS);
    const std::string why = ok ? "" : errnoText();
    if (std::fclose(f) != 0 || !ok) {
      std::remove(temp_path_.c_str());
      throw std::runtime_error("cannot write " + temp_path_ + ": " + (ok ? errnoText() : why));
    }
    batch->add(temp_path_, final_path_);
    return;
  }
  // sync before the rename, so that a crash cannot leave a final name on an empty file
  const bool ok = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  const std::string why = ok ? "" : errnoText();
  if (std::fclose(f) != 0 || !ok) {
    std::remove(temp_path_.c_str());
    throw std::runtime_error("cannot write " + temp_path_ + ": " + (ok ? errnoText() : why));
  }
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
    const std::string e = errnoText();
    std::remove(temp_path_.c_str());
    throw std::runtime_error("cannot rename " + temp_path_ + " to " + final_path_ + ": " + e);
  }
}

void AtomicFile::discard() {
  if (!file_) return;
  std::fclose(file_);
  file_ = nullptr;
  std::remove(temp_path_.c_str());
}

// ---------------------------------------------------------------------------------------------
// CommitBatch

CommitBatch::CommitBatch() : previous_(t_batch) {
  t_batch = this;
}

CommitBatch::~CommitBatch() {
  if (!active_) return;
  release();
  removeTemporaries(0);
}

CommitBatch* CommitBatch::current() {
  return t_batch;
}

void CommitBatch::add(const std::string& temp_path, const std::string& final_path) {
  pending_.push_back({temp_path, final_path});
}

void CommitBatch::release() {
  active_ = false;
  if (t_batch == this) t_batch = previous_;
}

void CommitBatch::removeTemporaries(std::size_t from) {
  for (std::size_t k = from; k < pending_.size(); ++k) std::remove(pending_[k].temp.c_str());
}

void CommitBatch::finish() {
  if (!active_) throw std::logic_error("CommitBatch::finish called twice");
  release();
  // the data first, every file at once: their write-back was started at commit, and concurrent
  // fsyncs share the device's cache flushes (one round trip instead of one per file, measured in
  // docs/bench/process.md); through the pool, so a thread the system refuses is no abort
  std::vector<int> errors(pending_.size(), 0);
  parallelFor(static_cast<long>(pending_.size()), static_cast<int>(pending_.size()),
              [&](long k) { errors[k] = syncPath(pending_[k].temp, 0) ? 0 : errno; });
  for (std::size_t k = 0; k < pending_.size(); ++k)
    if (errors[k] != 0) {
      removeTemporaries(0);
      throw std::runtime_error("cannot write " + pending_[k].temp + ": " +
                               std::strerror(errors[k]));
    }
  std::set<std::string> dirs;
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    const Pending& p = pending_[k];
    if (std::rename(p.temp.c_str(), p.final_path.c_str()) != 0) {
      const std::string e = errnoText();
      removeTemporaries(k);
      throw std::runtime_error("cannot rename " + p.temp + " to " + p.final_path + ": " + e);
    }
    const std::string dir = fs::path(p.final_path).parent_path().string();
    dirs.insert(dir.empty() ? "." : dir);
  }
  // the renames: one fsync per directory
  for (const std::string& d : dirs)
    if (!syncPath(d, O_DIRECTORY))
      throw std::runtime_error("cannot sync the directory " + d + ": " + errnoText());
}

void writeFileAtomically(const std::string& path, const std::string& contents) {
  AtomicFile f(path);
  f.write(contents);
  f.commit();
}

}  // namespace metrosync
