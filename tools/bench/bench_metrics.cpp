#include "tools/bench/bench_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace metrosync::bench {

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string benchNumber(double v, int precision, Notation notation) {
  return std::isfinite(v) ? numberText(v, precision, notation) : std::string();
}

std::string rowsVerdict(int met, int measured) {
  if (measured <= 0) return "not measured";
  if (met >= measured) return "met in all " + std::to_string(measured) + " rows";
  return "NOT met in " + std::to_string(measured - met) + " of " + std::to_string(measured) +
         " rows";
}

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
bool usable(const WorkPoint& p) {
  return std::isfinite(p.error) && std::isfinite(p.time_s) && p.error > 0 && p.time_s > 0;
}
}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<WorkPoint> paretoFront(std::vector<WorkPoint> points) {
  points.erase(
      std::remove_if(points.begin(), points.end(), [](const WorkPoint& p) { return !usable(p); }),
      points.end());
  std::sort(points.begin(), points.end(), [](const WorkPoint& a, const WorkPoint& b) {
    return a.error < b.error || (a.error == b.error && a.time_s < b.time_s);
  });
  // from the most accurate run up: keep a run only if it is cheaper than every more accurate one
  std::vector<WorkPoint> front;
  double cheapest = std::numeric_limits<double>::infinity();
  for (const WorkPoint& p : points) {
    if (p.time_s < cheapest) {
      if (!front.empty() && front.back().error == p.error) front.pop_back();
      front.push_back(p);
      cheapest = p.time_s;
    }
  }
  return front;
}

double timeAtError(const std::vector<WorkPoint>& front, double error) {
  if (front.empty() || !(error > 0)) return kNaN;
  // tolerate rounding at the ends
  const double lo = front.front().error * (1 - 1e-12), hi = front.back().error * (1 + 1e-12);
  if (error < lo || error > hi) return kNaN;
  if (front.size() == 1) return front.front().time_s;
  for (size_t k = 0; k + 1 < front.size(); ++k) {
    const WorkPoint& a = front[k];
    const WorkPoint& b = front[k + 1];
    if (error <= b.error * (1 + 1e-12)) {
      const double u =
          (std::log(error) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
      const double uc = std::clamp(u, 0.0, 1.0);
      return std::exp(std::log(a.time_s) + uc * (std::log(b.time_s) - std::log(a.time_s)));
    }
  }
  return front.back().time_s;
}

std::vector<EqualErrorRatio> ratiosAtEqualError(const std::vector<WorkPoint>& a,
                                                const std::vector<WorkPoint>& b) {
  std::vector<EqualErrorRatio> out;
  if (a.empty() || b.empty()) return out;
  const double lo = std::max(a.front().error, b.front().error);
  const double hi = std::min(a.back().error, b.back().error);
  if (!(lo <= hi)) return out;
  std::vector<double> errors = {lo};
  for (int k = static_cast<int>(std::ceil(std::log10(lo))); std::pow(10.0, k) < hi; ++k)
    if (std::pow(10.0, k) > lo) errors.push_back(std::pow(10.0, k));
  if (hi > lo) errors.push_back(hi);
  for (double e : errors) {
    EqualErrorRatio r;
    r.error = e;
    r.time_a_s = timeAtError(a, e);
    r.time_b_s = timeAtError(b, e);
    if (std::isfinite(r.time_a_s) && std::isfinite(r.time_b_s)) out.push_back(r);
  }
  return out;
}

double geometricMeanRatio(const std::vector<EqualErrorRatio>& r) {
  if (r.empty()) return kNaN;
  double s = 0;
  for (const auto& x : r) s += std::log(x.ratio());
  return std::exp(s / static_cast<double>(r.size()));
}

}  // namespace metrosync::bench
