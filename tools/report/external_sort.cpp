#include "tools/report/external_sort.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <queue>
#include <stdexcept>

#include "sim/record/private_dir.h"

namespace metrosync {

namespace {

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File openRun(const PrivateDir& tmp, const std::string& name) {
  const int fd = tmp.openForReading(name);
  std::FILE* f = fd >= 0 ? ::fdopen(fd, "r") : nullptr;
  if (!f) {
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("cannot read back " + tmp.path() + "/" + name + ": " +
                             std::strerror(errno));
  }
  return File(f, &std::fclose);
}

// One run being read: its current line ("INDEX\tLINE"), split.
struct RunCursor {
  File file{nullptr, &std::fclose};
  char* buf = nullptr;
  std::size_t cap = 0;
  long index = 0;
  std::string line;
  bool next() {
    const ssize_t len = ::getline(&buf, &cap, file.get());
    if (len <= 0) return false;
    char* tab = static_cast<char*>(std::memchr(buf, '\t', static_cast<std::size_t>(len)));
    if (!tab) throw std::runtime_error("a damaged sort run");
    index = std::strtol(buf, nullptr, 10);
    line.assign(tab + 1, static_cast<std::size_t>(len - (tab + 1 - buf) - 1));
    return true;
  }
  ~RunCursor() { std::free(buf); }
};

// The lines of `runs` merged in ascending index; ties in the order of the runs.
void mergeRuns(const PrivateDir& tmp, const std::vector<std::string>& runs,
               const std::function<void(long, const std::string&)>& visit) {
  std::vector<RunCursor> cursors(runs.size());
  using Head = std::pair<long, std::size_t>;  // index, run
  std::priority_queue<Head, std::vector<Head>, std::greater<Head>> heads;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    cursors[r].file = openRun(tmp, runs[r]);
    if (cursors[r].next()) heads.push({cursors[r].index, r});
  }
  while (!heads.empty()) {
    const std::size_t r = heads.top().second;
    heads.pop();
    visit(cursors[r].index, cursors[r].line);
    if (cursors[r].next()) heads.push({cursors[r].index, r});
  }
}

// Writes "INDEX\tLINE" lines to a new run file; throws on a write error.
class RunWriter {
 public:
  RunWriter(PrivateDir& tmp, const std::string& name)
      : name_(tmp.path() + "/" + name), file_(::fdopen(tmp.createOpen(name), "w"), &std::fclose) {
    if (!file_) throw std::runtime_error("cannot write " + name_);
  }
  void put(long index, const std::string& line) {
    if (std::fprintf(file_.get(), "%ld\t", index) < 0 ||
        std::fwrite(line.data(), 1, line.size(), file_.get()) != line.size() ||
        std::fputc('\n', file_.get()) == EOF)
      throw std::runtime_error("cannot write " + name_ + ": " + std::strerror(errno));
  }
  void close() {
    if (std::fclose(file_.release()) != 0)
      throw std::runtime_error("cannot write " + name_ + ": " + std::strerror(errno));
  }

 private:
  std::string name_;
  File file_;
};

}  // namespace

std::string temporaryFolder() {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::temp_directory_path(ec);
  return ec ? std::string("/tmp") : p.string();
}

ExternalSort::ExternalSort(const std::string& folder, std::size_t chunk_bytes)
    : folder_(folder), chunk_bytes_(chunk_bytes) {}

ExternalSort::~ExternalSort() = default;

void ExternalSort::add(long index, std::string line) {
  bytes_ += line.size() + sizeof(long);
  chunk_.emplace_back(index, std::move(line));
  max_held_ = std::max(max_held_, chunk_.size());
  if (bytes_ > chunk_bytes_) spill();
}

void ExternalSort::spill() {
  if (chunk_.empty()) return;
  if (!tmp_) tmp_ = std::make_unique<PrivateDir>(folder_);
  std::stable_sort(chunk_.begin(), chunk_.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  const std::string name = "run" + std::to_string(next_run_++);
  RunWriter w(*tmp_, name);
  for (const auto& [g, line] : chunk_) w.put(g, line);
  w.close();
  runs_.push_back(name);
  chunk_.clear();
  chunk_.shrink_to_fit();
  bytes_ = 0;
}

void ExternalSort::mergeDown() {
  while (runs_.size() > kSortFanIn) {  // the first kSortFanIn runs become one, in their place
    const std::vector<std::string> group(runs_.begin(), runs_.begin() + kSortFanIn);
    const std::string name = "run" + std::to_string(next_run_++);
    RunWriter w(*tmp_, name);
    mergeRuns(*tmp_, group, [&](long g, const std::string& line) { w.put(g, line); });
    w.close();
    for (const auto& r : group) ::unlinkat(tmp_->fd(), r.c_str(), 0);
    runs_.erase(runs_.begin(), runs_.begin() + kSortFanIn);
    runs_.insert(runs_.begin(), name);
  }
}

void ExternalSort::forEach(const std::function<void(long, const std::string&)>& visit) {
  if (runs_.empty()) {  // everything fits in one chunk: sorted in memory
    std::stable_sort(chunk_.begin(), chunk_.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [g, line] : chunk_) visit(g, line);
    return;
  }
  spill();
  mergeDown();
  mergeRuns(*tmp_, runs_, visit);
}

void ExternalSort::forEachIndex(
    const std::function<void(long, const std::vector<std::string>&)>& visit) {
  std::vector<std::string> lines;
  long current = 0;
  forEach([&](long g, const std::string& line) {
    if (!lines.empty() && g != current) {
      visit(current, lines);
      lines.clear();
    }
    current = g;
    lines.push_back(line);
  });
  if (!lines.empty()) visit(current, lines);
}

}  // namespace metrosync
