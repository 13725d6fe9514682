#include "tools/report/envelope_store.h"

#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <stdexcept>

#include "sim/record/envelope.h"
#include "sim/record/safe_open.h"

namespace metrosync {

std::string envelopeStoreHeader(int n) {
  return "point," + envelopeHeader(n);
}

namespace {

// The whole decompressed text up to the first damaged byte (a truncated member ends it).
std::string readGzipText(const std::string& path) {
  const int fd = openRegularForReading(path);  // never a link's target, never a FIFO
  if (fd < 0) return "";
  gzFile f = gzdopen(fd, "rb");
  if (!f) {
    ::close(fd);
    return "";
  }
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const int k = gzread(f, buf, sizeof buf);
    if (k <= 0) break;  // end, or a damaged tail: keep what came before
    text.append(buf, static_cast<size_t>(k));
  }
  gzclose(f);
  return text;
}

// One gzip member holding `text`, appended to `path`.
void appendGzipMember(const std::string& path, const std::string& text) {
  const int fd = openOutputFile(path, false, true);
  gzFile f = gzdopen(fd, "ab");
  if (!f) ::close(fd);
  if (!f) throw std::runtime_error(path + ": cannot open for appending");
  const bool ok = text.empty() || gzwrite(f, text.data(), static_cast<unsigned>(text.size())) ==
                                      static_cast<int>(text.size());
  if (gzclose(f) != Z_OK || !ok) throw std::runtime_error(path + ": write failed");
}

}  // namespace

std::map<long, std::vector<std::string>> readEnvelopeStore(const std::string& path) {
  std::map<long, std::vector<std::string>> points;
  const std::string text = readGzipText(path);
  if (text.empty()) return points;
  size_t at = text.find('\n');
  if (at == std::string::npos || text.compare(0, 10, "point,tau,") != 0)
    throw std::runtime_error(path + ": not an envelope store (header point,tau,...)");
  std::map<long, std::vector<std::string>> open;
  for (size_t start = at + 1; start < text.size(); start = at + 1) {
    at = text.find('\n', start);
    if (at == std::string::npos) break;  // a line without its newline: cut short
    const std::string line = text.substr(start, at - start);
    const size_t comma = line.find(',');
    if (comma == std::string::npos || line.compare(0, 6, "point,") == 0) continue;  // headers
    if (line.compare(0, 5, "#end,") == 0) {
      const long g = std::stol(line.substr(5));
      const long rows = std::stol(line.substr(line.find(',', 5) + 1));
      if (static_cast<long>(open[g].size()) == rows) points[g] = std::move(open[g]);
      open.erase(g);
      continue;
    }
    open[std::stol(line.substr(0, comma))].push_back(line.substr(comma + 1));
  }
  return points;
}

EnvelopeStore::EnvelopeStore(const std::string& path, int n, bool fresh, const std::set<long>& keep)
    : path_(path) {
  std::map<long, std::vector<std::string>> kept;
  if (!fresh) kept = readEnvelopeStore(path);
  // a new file (or the old one without its damaged tail), written whole, then appended to
  std::string text = envelopeStoreHeader(n) + "\n";
  for (const auto& [g, rows] : kept) {
    if (!keep.count(g)) continue;
    for (const auto& row : rows) text += std::to_string(g) + "," + row + "\n";
    text += "#end," + std::to_string(g) + "," + std::to_string(rows.size()) + "\n";
  }
  const std::string tmp = path + ".new";
  std::filesystem::remove(tmp);
  appendGzipMember(tmp, text);
  std::filesystem::rename(tmp, path);
}

void EnvelopeStore::append(long g, const std::vector<std::string>& rows) {
  std::string text;
  const std::string prefix = std::to_string(g) + ",";
  for (const auto& row : rows) text += prefix + row + "\n";
  text += "#end," + std::to_string(g) + "," + std::to_string(rows.size()) + "\n";
  std::lock_guard<std::mutex> lock(mutex_);
  appendGzipMember(path_, text);
}

}  // namespace metrosync
