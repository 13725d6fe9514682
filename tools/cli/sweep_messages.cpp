#include "tools/cli/sweep_messages.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace metrosync::cli {

namespace {

// Appends fixed-size values and length-prefixed strings/arrays; native byte order (the ranks of
// one sweep run the same binary).
class Writer {
 public:
  template <class T>
  void put(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void text(const std::string& s) {
    put<std::int64_t>(static_cast<std::int64_t>(s.size()));
    bytes_ += s;
  }
  void doubles(const std::vector<double>& v) {
    put<std::int64_t>(static_cast<std::int64_t>(v.size()));
    for (double x : v) put(x);
  }
  void longs(const std::vector<long>& v) {
    put<std::int64_t>(static_cast<std::int64_t>(v.size()));
    for (long x : v) put<std::int64_t>(x);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(const std::string& b) : b_(b) {}
  template <class T>
  T get() {
    if (at_ + sizeof(T) > b_.size()) throw std::runtime_error("sweep message cut short");
    T v;
    std::memcpy(&v, b_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  size_t length() {
    const auto n = get<std::int64_t>();
    if (n < 0 || static_cast<size_t>(n) > b_.size() - at_)
      throw std::runtime_error("sweep message: bad length");
    return static_cast<size_t>(n);
  }
  std::string text() {
    const size_t n = length();
    std::string s = b_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::vector<double> doubles() {
    std::vector<double> v(length());
    for (double& x : v) x = get<double>();
    return v;
  }
  std::vector<long> longs() {
    std::vector<long> v(length());
    for (long& x : v) x = static_cast<long>(get<std::int64_t>());
    return v;
  }
  void end() const {
    if (at_ != b_.size()) throw std::runtime_error("sweep message: trailing bytes");
  }

 private:
  const std::string& b_;
  size_t at_ = 0;
};

void putPoint(Writer& w, const SweepPoint& p) {
  w.put<std::int64_t>(p.index);
  w.text(p.regime);
  w.doubles(p.A);
  w.doubles(p.psi);
  w.put(p.r);
  w.put(p.s);
  w.text(p.clusters);
  w.put(p.tau);
  w.put<std::uint8_t>(p.complete ? 1 : 0);
  w.text(p.message);
  w.put(p.in_phase_fraction);
  w.put(p.wall_seconds);
  w.put(p.cpu_seconds);
  w.put(p.engine_cpu_seconds);
}

SweepPoint getPoint(Reader& r) {
  SweepPoint p;
  p.index = static_cast<long>(r.get<std::int64_t>());
  p.regime = r.text();
  p.A = r.doubles();
  p.psi = r.doubles();
  p.r = r.get<double>();
  p.s = r.get<double>();
  p.clusters = r.text();
  p.tau = r.get<double>();
  p.complete = r.get<std::uint8_t>() != 0;
  p.message = r.text();
  p.in_phase_fraction = r.get<double>();
  p.wall_seconds = r.get<double>();
  p.cpu_seconds = r.get<double>();
  p.engine_cpu_seconds = r.get<double>();
  return p;
}

}  // namespace

std::string encodeReport(const SweepReport& rep) {
  Writer w;
  w.put<std::int64_t>(rep.want);
  w.put<std::uint8_t>(rep.done ? 1 : 0);
  w.put<std::int64_t>(static_cast<std::int64_t>(rep.points.size()));
  for (const auto& p : rep.points) putPoint(w, p);
  w.longs(rep.unrun);
  return w.bytes();
}

SweepReport decodeReport(const std::string& bytes) {
  Reader r(bytes);
  SweepReport rep;
  rep.want = static_cast<long>(r.get<std::int64_t>());
  rep.done = r.get<std::uint8_t>() != 0;
  const size_t n = r.length();
  for (size_t k = 0; k < n; ++k) rep.points.push_back(getPoint(r));
  rep.unrun = r.longs();
  r.end();
  return rep;
}

std::string encodeWork(const SweepWork& work) {
  Writer w;
  w.put<std::uint8_t>(work.last ? 1 : 0);
  w.longs(work.indices);
  return w.bytes();
}

SweepWork decodeWork(const std::string& bytes) {
  Reader r(bytes);
  SweepWork work;
  work.last = r.get<std::uint8_t>() != 0;
  work.indices = r.longs();
  r.end();
  return work;
}

}  // namespace metrosync::cli
