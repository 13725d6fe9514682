#include "tools/report/envelope_store.h"

#include <unistd.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include "sim/record/envelope.h"
#include "sim/record/safe_open.h"

namespace metrosync {

std::string envelopeStoreHeader(int n) {
  return "point," + envelopeHeader(n);
}

namespace {

// Calls line(text) for each whole decompressed line (without its newline) up to the first damaged
// byte (a truncated member ends it); false when the file is absent.
bool forEachGzipLine(const std::string& path, const std::function<void(const std::string&)>& line) {
  const int fd = openRegularForReading(path);  // never a link's target, never a FIFO
  if (fd < 0) return false;
  gzFile f = gzdopen(fd, "rb");
  if (!f) {
    ::close(fd);
    return false;
  }
  std::string pending;  // the current line's start
  char buf[1 << 16];
  for (;;) {
    const int k = gzread(f, buf, sizeof buf);
    if (k <= 0) break;  // end, or a damaged tail: keep what came before
    std::size_t from = 0;
    for (const char* nl;
         (nl = static_cast<const char*>(std::memchr(buf + from, '\n', k - from)));) {
      pending.append(buf + from, static_cast<std::size_t>(nl - (buf + from)));
      line(pending);
      pending.clear();
      from = static_cast<std::size_t>(nl - buf) + 1;
    }
    pending.append(buf + from, static_cast<std::size_t>(k) - from);
  }
  gzclose(f);
  return true;  // a last line without its newline: cut short, dropped
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

void forEachStoredEnvelope(
    const std::string& path,
    const std::function<void(long, const std::vector<std::string>&)>& visit) {
  bool header = true;
  std::map<long, std::vector<std::string>> open;  // the points whose #end is still to come
  forEachGzipLine(path, [&](const std::string& line) {
    if (header) {
      if (line.compare(0, 10, "point,tau,") != 0)
        throw std::runtime_error(path + ": not an envelope store (header point,tau,...)");
      header = false;
      return;
    }
    const size_t comma = line.find(',');
    if (comma == std::string::npos || line.compare(0, 6, "point,") == 0) return;  // headers
    if (line.compare(0, 5, "#end,") == 0) {
      const long g = std::stol(line.substr(5));
      const long rows = std::stol(line.substr(line.find(',', 5) + 1));
      const auto it = open.find(g);
      if (it != open.end() && static_cast<long>(it->second.size()) == rows) visit(g, it->second);
      if (it != open.end()) open.erase(it);
      return;
    }
    open[std::stol(line.substr(0, comma))].push_back(line.substr(comma + 1));
  });
}

std::map<long, std::vector<std::string>> readEnvelopeStore(const std::string& path) {
  std::map<long, std::vector<std::string>> points;
  forEachStoredEnvelope(path,
                        [&](long g, const std::vector<std::string>& rows) { points[g] = rows; });
  return points;
}

EnvelopeStore::EnvelopeStore(const std::string& path, int n, bool fresh,
                             const std::function<bool(long)>& keep)
    : path_(path), check_(path) {
  check_.line(envelopeStoreHeader(n));
  // a new file (or the old one without its damaged tail and the points not kept), written as one
  // member point by point (one point's rows in memory at a time), then appended to
  const std::string tmp = path + ".new";
  std::filesystem::remove(tmp);
  const int fd = openOutputFile(tmp, true, false);
  gzFile f = gzdopen(fd, "wb");
  if (!f) ::close(fd);
  if (!f) throw std::runtime_error(tmp + ": cannot open for writing");
  bool ok = true;
  const auto put = [&](const std::string& text) {
    ok = ok && gzwrite(f, text.data(), static_cast<unsigned>(text.size())) ==
                   static_cast<int>(text.size());
  };
  std::set<long> written;
  try {
    put(envelopeStoreHeader(n) + "\n");
    if (!fresh)
      forEachStoredEnvelope(path, [&](long g, const std::vector<std::string>& rows) {
        if (!keep || !keep(g) || !written.insert(g).second) return;  // a point stored twice: once
        for (const auto& row : rows) put(std::to_string(g) + "," + row + "\n");
        put("#end," + std::to_string(g) + "," + std::to_string(rows.size()) + "\n");
      });
  } catch (...) {
    gzclose(f);
    throw;
  }
  if (gzclose(f) != Z_OK || !ok) throw std::runtime_error(tmp + ": write failed");
  std::filesystem::rename(tmp, path);
}

void EnvelopeStore::append(long g, const std::vector<std::string>& rows) {
  std::string text;
  const std::string prefix = std::to_string(g) + ",";
  for (const auto& row : rows) text += prefix + row + "\n";
  text += "#end," + std::to_string(g) + "," + std::to_string(rows.size()) + "\n";
  std::lock_guard<std::mutex> lock(mutex_);
  check_.text(text);  // no non-finite number (sim/record/finite_check.h)
  appendGzipMember(path_, text);
}

}  // namespace metrosync
