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

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/parallel/worker_pool.h"

namespace metrosync {

namespace {

constexpr long kMaxAxisCount = 1000000;

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

// "KEY=V1,V2,..." or "KEY=V": the values as listed (one or more, in any order), for the paper's
// runs (mu = 0.2, 0.3, 0.4) and the Python module's vary=[...]. `a` holds the key and spec.
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
  if (static_cast<long>(a.values.size()) > kMaxAxisCount)
    throw SweepInputError("--vary " + text + ": a list takes at most " +
                          std::to_string(kMaxAxisCount) + " values");
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
  return numberText(v, 15);
}

namespace {

// The COUNT values of a range axis: even steps in the value, or in log(value) for ":log"; the
// ends exactly FROM and TO (when included).
void rangeValues(SweepAxis& a) {
  const double lo = a.log ? std::log(a.from) : a.from;
  const double hi = a.log ? std::log(a.to) : a.to;
  for (long k = 0; k < a.count; ++k) {
    const long steps = a.open ? a.count : a.count - 1;
    double v = a.from;
    if (k > 0 && !a.open && k == a.count - 1) {
      v = a.to;
    } else if (k > 0) {
      const double x = lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(steps);
      v = a.log ? std::exp(x) : x;
    }
    a.texts.push_back(sweepValueText(v));
    a.values.push_back(std::strtod(a.texts.back().c_str(), nullptr));
  }
}

// The flags after COUNT: "open" and/or "log", each at most once.
void rangeFlags(SweepAxis& a, const std::vector<std::string>& f, const std::string& text) {
  for (size_t k = 3; k < f.size(); ++k) {
    const std::string flag = trim(f[k]);
    bool& on = flag == "open" ? a.open : a.log;
    if ((flag != "open" && flag != "log") || on)
      throw SweepInputError("--vary " + text +
                            ": after COUNT only ':open' (TO left out) and ':log' "
                            "(log spacing) may follow, each once; found '" +
                            f[k] + "'");
    on = true;
  }
  if (a.log && !(a.from > 0.0 && a.to > 0.0))
    throw SweepInputError("--vary " + text + ": ':log' needs FROM > 0 and TO > 0 (log spacing " +
                          "of " + sweepValueText(a.from) + " to " + sweepValueText(a.to) + ")");
  if (a.log && a.from > a.to)
    throw SweepInputError("--vary " + text + ": ':log' needs FROM <= TO (got FROM = " +
                          sweepValueText(a.from) + " > TO = " + sweepValueText(a.to) + ")");
}

}  // namespace

SweepAxis parseVary(const std::string& text) {
  const std::string usage = "--vary " + text +
                            ": expected KEY=FROM:TO:COUNT[:open][:log] or KEY=V1,V2,... (e.g. "
                            "platform.friction.mu=0:0.8:41)";
  const size_t eq = text.find('=');
  if (eq == std::string::npos) throw SweepInputError(usage);
  SweepAxis a;
  a.key = trim(text.substr(0, eq));
  a.spec = text.substr(eq + 1);
  if (a.key.empty() || a.key.find_first_of(" \t:=") != std::string::npos)
    throw SweepInputError(usage + ": no key before '='");
  if (trim(a.spec).empty()) throw SweepInputError("--vary " + text + ": no values after '='");
  // a list, or one value alone (no ':')
  if (a.spec.find(',') != std::string::npos || a.spec.find(':') == std::string::npos)
    return listAxis(a, text);
  const std::vector<std::string> f = split(a.spec, ':');
  if (f.size() < 3 || f.size() > 5) throw SweepInputError(usage);
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
  rangeFlags(a, f, text);
  rangeValues(a);
  return a;
}

SweepGrid::SweepGrid(std::vector<SweepAxis> axes, long max_points) : axes_(std::move(axes)) {
  if (axes_.empty()) throw SweepInputError("sweep: at least one --vary KEY=FROM:TO:COUNT");
  for (size_t a = 0; a < axes_.size(); ++a)
    for (size_t b = a + 1; b < axes_.size(); ++b)
      if (axes_[a].key == axes_[b].key)
        throw SweepInputError("sweep: --vary " + axes_[a].key + " given twice");
  const long cap = std::min(max_points, kMaxForcedGridPoints);
  size_ = 1;
  for (const auto& a : axes_) {
    if (a.count < 1 || a.texts.size() != static_cast<size_t>(a.count))
      throw SweepInputError("sweep: axis " + a.key + " has no values");
    if (size_ > cap / a.count) {
      std::string counts;
      for (const auto& b : axes_) counts += (counts.empty() ? "" : " x ") + std::to_string(b.count);
      throw SweepInputError("sweep: " + counts + " is more than " + std::to_string(cap) +
                            " grid points" +
                            (cap < kMaxForcedGridPoints ? " (add --force to run it anyway)" : ""));
    }
    size_ *= a.count;
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
                    {"log", a.log},
                    {"values", a.texts}});
  nlohmann::json j = {{"axes", axes}, {"points", size_}};
  if (basin_.samples > 0)
    j["basin"] = {{"samples", basin_.samples}, {"seed", basin_.seed}, {"random", basin_.random}};
  return j;
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
      a.log = ja.value("log", false);  // written since axes could be log-spaced
      a.texts = ja.at("values").get<std::vector<std::string>>();
      for (const auto& t : a.texts) a.values.push_back(parseSweepNumber(t));
      axes.push_back(std::move(a));
    }
    SweepGrid grid(std::move(axes), kMaxForcedGridPoints);
    if (j.contains("basin")) {
      const auto& b = j.at("basin");
      grid.setBasin({b.at("samples").get<long>(), b.at("seed").get<std::uint64_t>(),
                     b.at("random").get<std::vector<std::string>>()});
    }
    return grid;
  } catch (const nlohmann::json::exception& e) {
    throw SweepInputError(std::string("not a sweep grid: ") + e.what());
  }
}

std::vector<size_t> mapAxes(const SweepGrid& grid, const std::string& text) {
  std::vector<size_t> axes;
  if (trim(text).empty()) {
    for (size_t k = 0; k < grid.axes().size() && axes.size() < 2; ++k)
      if (grid.axes()[k].count > 1) axes.push_back(k);
    if (axes.empty()) axes.push_back(0);
    return axes;
  }
  const std::vector<std::string> keys = split(text, ',');
  if (keys.size() > 2) throw SweepInputError("--map " + text + ": one or two keys, KEY1,KEY2");
  for (const auto& key : keys) {
    size_t k = 0;
    while (k < grid.axes().size() && grid.axes()[k].key != trim(key)) ++k;
    if (k == grid.axes().size()) {
      std::string known;
      for (const auto& a : grid.axes()) known += (known.empty() ? "" : ", ") + a.key;
      throw SweepInputError("--map " + text + ": '" + trim(key) +
                            "' is not a --vary key of this sweep (" + known + ")");
    }
    if (std::find(axes.begin(), axes.end(), k) != axes.end())
      throw SweepInputError("--map " + text + ": '" + trim(key) + "' named twice");
    axes.push_back(k);
  }
  return axes;
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

int runSweepPoints(long grid_size, const std::function<bool(long)>& wanted, int jobs,
                   const std::function<std::optional<SweepPoint>(long)>& run_point,
                   const std::function<void(const SweepPoint&)>& finished,
                   const std::function<bool()>& stop) {
  std::mutex lock;  // guards next, finished() and the first error
  long next = 0;
  bool failed = false;
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
      failed = true;
      throw;  // the pool rethrows the first one
    }
  };
  // never more threads than points to run: count the wanted ones up to `jobs`
  long work = 0;
  const long most = jobs > 0 ? jobs : workerCount(jobs, grid_size);
  for (long g = 0; g < grid_size && work < most; ++g) work += wanted(g);
  return runWorkers(workerCount(jobs, work), worker);
}

int runSweepPoints(const std::vector<long>& todo, int jobs,
                   const std::function<std::optional<SweepPoint>(long)>& run_point,
                   const std::function<void(const SweepPoint&)>& finished,
                   const std::function<bool()>& stop) {
  return runSweepPoints(
      static_cast<long>(todo.size()), [](long) { return true; }, jobs,
      [&](long k) { return run_point(todo[k]); }, finished, stop);
}

long shardSize(const SweepGrid& grid, const SweepShard& shard) {
  const long first = shard.k - 1;  // g = first, first + n, ...
  return grid.size() > first ? (grid.size() - 1 - first) / shard.n + 1 : 0;
}

}  // namespace metrosync
