#include "sim/record/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

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

}  // namespace

// ".NAME.<pid>.part" next to NAME: hidden, and plainly not a finished output.
std::string temporaryPathFor(const std::string& final_path) {
  const fs::path p(final_path);
  const std::string name = "." + p.filename().string() + "." + std::to_string(::getpid()) + ".part";
  return (p.parent_path() / name).string();
}

// ---------------------------------------------------------------------------------------------
// AtomicFile

AtomicFile::AtomicFile(std::string final_path)
    : final_path_(std::move(final_path)), temp_path_(temporaryPathFor(final_path_)) {
  file_ = std::fopen(temp_path_.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot write " + temp_path_ + ": " + errnoText());
  // a large buffer: rows are small and many
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 16);
  last_flush_ = std::chrono::steady_clock::now();
}

AtomicFile::~AtomicFile() {
  discard();
}

void AtomicFile::write(const std::string& text) {
  if (!file_) throw std::logic_error("write to a closed file " + final_path_);
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw std::runtime_error("cannot write " + temp_path_ + ": " + errnoText());
}

void AtomicFile::writeLine(const std::string& line) {
  write(line);
  write("\n");
  // flush about once a second (the clock costs far less than formatting the line)
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

void writeFileAtomically(const std::string& path, const std::string& contents) {
  AtomicFile f(path);
  f.write(contents);
  f.commit();
}

}  // namespace metrosync
