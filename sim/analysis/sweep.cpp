#include "sim/analysis/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

namespace metrosync {

namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kTwoPi = 6.283185307179586;
constexpr long kMaxAxisCount = 1000000;
constexpr long kMaxGridPoints = 10000000;

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// A plain decimal number, the whole text; nullopt otherwise.
std::optional<double> plainNumber(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  // strtod also reads "inf", "nan" and hexadecimal: not what a grid bound looks like
  if (t.find_first_of("nNiIxX") != std::string::npos) return std::nullopt;
  return v;
}

std::optional<long> plainInteger(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty() || t.size() > 12 || t.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::stol(t);
}

// "KEY=V1,V2,...": the values as listed (at least two, in any order), for the paper's runs
// (mu = 0.2, 0.3, 0.4) and the Python module's vary=[...]. `a` holds the key and spec.
SweepAxis listAxis(SweepAxis a, const std::string& text) {
  for (const auto& item : split(a.spec, ',')) {
    double v = 0.0;
    try {
      v = parseSweepNumber(item);
    } catch (const SweepInputError& e) {
      throw SweepInputError("--vary " + text + ": " + e.what());
    }
    a.texts.push_back(sweepValueText(v));
    a.values.push_back(std::strtod(a.texts.back().c_str(), nullptr));
  }
  if (a.values.size() < 2 || static_cast<long>(a.values.size()) > kMaxAxisCount)
    throw SweepInputError("--vary " + text + ": a list needs 2 to " +
                          std::to_string(kMaxAxisCount) + " values (one value: V:V:1)");
  a.count = static_cast<long>(a.values.size());
  a.from = a.values.front();
  a.to = a.values.back();
  return a;
}

}  // namespace

// ---- the grid -----------------------------------------------------------------------------------

double parseSweepNumber(const std::string& text) {
  const std::string t = trim(text);
  if (auto v = plainNumber(t)) return *v;
  const size_t at = t.find("pi");
  if (at == std::string::npos || t.find("pi", at + 2) != std::string::npos)
    throw SweepInputError("'" + text + "' is not a number (nor a multiple of pi such as 2pi)");
  // [coefficient][*]pi[/denominator]
  std::string coef = trim(t.substr(0, at));
  if (!coef.empty() && coef.back() == '*') coef = trim(coef.substr(0, coef.size() - 1));
  double c = 1.0;
  if (coef == "-") {
    c = -1.0;
  } else if (coef == "+" || coef.empty()) {
    c = 1.0;
  } else if (auto v = plainNumber(coef)) {
    c = *v;
  } else {
    throw SweepInputError("'" + text + "': '" + coef + "' before pi is not a number");
  }
  const std::string rest = trim(t.substr(at + 2));
  double den = 1.0;
  if (!rest.empty()) {
    auto d = rest[0] == '/' ? plainNumber(rest.substr(1)) : std::nullopt;
    if (!d || *d == 0.0)
      throw SweepInputError("'" + text + "': expected pi or pi/NUMBER, found '" + rest + "'");
    den = *d;
  }
  return c * kPi / den;
}

std::string sweepValueText(double v) {
  if (v == 0.0) return "0";  // and not "-0"
  // 15 digits: what the user meant (0.3, not 0.30000000000000004); the point's value is then
  // the number this text denotes, the same in the rig and in regimes.csv
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

SweepAxis parseVary(const std::string& text) {
  const std::string usage =
      "--vary " + text + ": expected KEY=FROM:TO:COUNT[:open] (e.g. platform.friction.mu=0:0.8:41)";
  const size_t eq = text.find('=');
  if (eq == std::string::npos) throw SweepInputError(usage);
  SweepAxis a;
  a.key = trim(text.substr(0, eq));
  a.spec = text.substr(eq + 1);
  if (a.key.empty() || a.key.find_first_of(" \t:=") != std::string::npos)
    throw SweepInputError(usage + ": no key before '='");
  if (a.spec.find(',') != std::string::npos) return listAxis(a, text);
  const std::vector<std::string> f = split(a.spec, ':');
  if (f.size() != 3 && f.size() != 4) throw SweepInputError(usage);
  try {
    a.from = parseSweepNumber(f[0]);
    a.to = parseSweepNumber(f[1]);
  } catch (const SweepInputError& e) {
    throw SweepInputError("--vary " + text + ": " + e.what());
  }
  const auto count = plainInteger(f[2]);
  if (!count || *count < 1 || *count > kMaxAxisCount)
    throw SweepInputError("--vary " + text + ": COUNT = '" + f[2] +
                          "' must be a whole number from 1 to " + std::to_string(kMaxAxisCount));
  a.count = *count;
  if (f.size() == 4) {
    if (trim(f[3]) != "open")
      throw SweepInputError("--vary " + text +
                            ": after COUNT only ':open' may follow (TO left out)");
    a.open = true;
  }
  for (long k = 0; k < a.count; ++k) {
    double v = a.from;
    if (a.open)
      v = a.from + (a.to - a.from) * static_cast<double>(k) / static_cast<double>(a.count);
    else if (a.count > 1)
      v = k == a.count - 1 ? a.to
                           : a.from + (a.to - a.from) * static_cast<double>(k) /
                                          static_cast<double>(a.count - 1);
    a.texts.push_back(sweepValueText(v));
    a.values.push_back(std::strtod(a.texts.back().c_str(), nullptr));
  }
  return a;
}

SweepGrid::SweepGrid(std::vector<SweepAxis> axes) : axes_(std::move(axes)) {
  if (axes_.empty()) throw SweepInputError("sweep: at least one --vary KEY=FROM:TO:COUNT");
  if (axes_.size() > 2)
    throw SweepInputError("sweep: at most two --vary (a regime map has two axes); got " +
                          std::to_string(axes_.size()));
  if (axes_.size() == 2 && axes_[0].key == axes_[1].key)
    throw SweepInputError("sweep: --vary " + axes_[0].key + " given twice");
  size_ = 1;
  for (const auto& a : axes_) {
    if (a.count < 1 || a.texts.size() != static_cast<size_t>(a.count))
      throw SweepInputError("sweep: axis " + a.key + " has no values");
    size_ *= a.count;
    if (size_ > kMaxGridPoints)
      throw SweepInputError("sweep: more than " + std::to_string(kMaxGridPoints) + " grid points");
  }
}

std::vector<long> SweepGrid::coordinates(long index) const {
  std::vector<long> c(axes_.size());
  for (size_t a = axes_.size(); a-- > 0;) {
    c[a] = index % axes_[a].count;
    index /= axes_[a].count;
  }
  return c;
}

std::vector<std::string> SweepGrid::overrides(long index) const {
  const std::vector<long> c = coordinates(index);
  std::vector<std::string> o;
  for (size_t a = 0; a < axes_.size(); ++a) o.push_back(axes_[a].key + "=" + axes_[a].texts[c[a]]);
  return o;
}

nlohmann::json SweepGrid::toJson() const {
  nlohmann::json axes = nlohmann::json::array();
  for (const auto& a : axes_)
    axes.push_back({{"key", a.key},
                    {"spec", a.spec},
                    {"from", a.from},
                    {"to", a.to},
                    {"count", a.count},
                    {"open", a.open},
                    {"values", a.texts}});
  return {{"axes", axes}, {"points", size_}};
}

SweepGrid SweepGrid::fromJson(const nlohmann::json& j) {
  try {
    std::vector<SweepAxis> axes;
    for (const auto& ja : j.at("axes")) {
      SweepAxis a;
      a.key = ja.at("key").get<std::string>();
      a.spec = ja.at("spec").get<std::string>();
      a.from = ja.at("from").get<double>();
      a.to = ja.at("to").get<double>();
      a.count = ja.at("count").get<long>();
      a.open = ja.at("open").get<bool>();
      a.texts = ja.at("values").get<std::vector<std::string>>();
      for (const auto& t : a.texts) a.values.push_back(parseSweepNumber(t));
      axes.push_back(std::move(a));
    }
    return SweepGrid(std::move(axes));
  } catch (const nlohmann::json::exception& e) {
    throw SweepInputError(std::string("not a sweep grid: ") + e.what());
  }
}

SweepShard parseShard(const std::string& text) {
  const std::vector<std::string> f = split(text, '/');
  const auto k = f.size() == 2 ? plainInteger(f[0]) : std::nullopt;
  const auto n = f.size() == 2 ? plainInteger(f[1]) : std::nullopt;
  if (!k || !n || *n < 1 || *k < 1 || *k > *n || *n > 1000000)
    throw SweepInputError("--shard " + text + ": expected K/N with 1 <= K <= N (e.g. 2/4)");
  return SweepShard{static_cast<int>(*k), static_cast<int>(*n)};
}

std::vector<long> shardIndices(const SweepGrid& grid, const SweepShard& shard) {
  std::vector<long> v;
  for (long g = shard.k - 1; g < grid.size(); g += shard.n) v.push_back(g);
  return v;
}

// ---- regimes.csv --------------------------------------------------------------------------------

double wrapToTwoPi(double angle_rad) {
  if (!std::isfinite(angle_rad)) return angle_rad;
  double w = std::fmod(angle_rad, kTwoPi);
  if (w < 0.0) w += kTwoPi;
  if (w >= kTwoPi) w = 0.0;  // -tiny + 2 pi rounds to 2 pi
  return w;
}

// ---- running ------------------------------------------------------------------------------------

void runSweepPoints(long grid_size, const std::function<bool(long)>& wanted, int jobs,
                    const std::function<std::optional<SweepPoint>(long)>& run_point,
                    const std::function<void(const SweepPoint&)>& finished,
                    const std::function<bool()>& stop) {
  std::mutex lock;  // guards next, finished() and the first error
  long next = 0;
  bool failed = false;
  std::exception_ptr first_error;
  auto take = [&]() -> long {  // the next wanted index, or -1; under the lock
    while (next < grid_size && !wanted(next)) ++next;
    return next < grid_size ? next++ : -1;
  };
  auto worker = [&] {
    try {
      for (;;) {
        long g;
        {
          std::lock_guard<std::mutex> l(lock);
          if (failed || stop() || (g = take()) < 0) return;
        }
        std::optional<SweepPoint> p = run_point(g);
        if (!p) continue;
        std::lock_guard<std::mutex> l(lock);
        if (!failed) finished(*p);
      }
    } catch (...) {
      std::lock_guard<std::mutex> l(lock);
      if (!first_error) first_error = std::current_exception();
      failed = true;
    }
  };
  const int threads = std::max(1, jobs);
  if (threads == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (first_error) std::rethrow_exception(first_error);
}

void runSweepPoints(const std::vector<long>& todo, int jobs,
                    const std::function<std::optional<SweepPoint>(long)>& run_point,
                    const std::function<void(const SweepPoint&)>& finished,
                    const std::function<bool()>& stop) {
  runSweepPoints(
      static_cast<long>(todo.size()), [](long) { return true; },
      std::min<long>(std::max(jobs, 1), std::max<long>(1, static_cast<long>(todo.size()))),
      [&](long k) { return run_point(todo[k]); }, finished, stop);
}

long shardSize(const SweepGrid& grid, const SweepShard& shard) {
  const long first = shard.k - 1;  // g = first, first + n, ...
  return grid.size() > first ? (grid.size() - 1 - first) / shard.n + 1 : 0;
}

}  // namespace metrosync
