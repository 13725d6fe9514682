#include "sim/analysis/continuation/exchanges.h"

#include <algorithm>
#include <cmath>

namespace metrosync::continuation {

namespace {

using Cd = std::complex<double>;
// The parameter values between the range's ends at which the metronomes' parameters are
// compared (besides the ends).
constexpr int kSamples = 7;

bool sameMetronome(const ScaledParams& a, int i, int j) {
  return a.nu[i] == a.nu[j] && a.J[i] == a.J[j] && a.theta_c[i] == a.theta_c[j] &&
         a.alpha[i] == a.alpha[j] && a.locked[i] == a.locked[j];
}

// sigma with copy_i * turn = z_sigma(i) within tolerance, each z used once, one class each.
std::optional<std::vector<int>> matched(const std::vector<Cd>& copy, const std::vector<Cd>& z,
                                        const std::vector<int>& classes, Cd turn,
                                        double tolerance) {
  const size_t n = copy.size();
  std::vector<int> sigma(n, -1);
  std::vector<bool> used(n, false);
  for (size_t i = 0; i < n; ++i) {
    const Cd w = copy[i] * turn;
    for (size_t k = 0; k < n && sigma[i] < 0; ++k)
      if (!used[k] && classes[k] == classes[i] && std::abs(w - z[k]) <= tolerance)
        sigma[i] = static_cast<int>(k), used[k] = true;
    if (sigma[i] < 0) return std::nullopt;
  }
  return sigma;
}

// The packed vector (a state or a tangent, the parameter last) of `from` exchanged into `to`.
Vec exchanged(const SlowFlowProblem& from, const SlowFlowProblem& to, const std::vector<int>& sigma,
              const Vec& y) {
  const int n = from.system().n;
  const std::vector<Cd> z = from.unpack(y.head(n));
  std::vector<Cd> w(z.size());
  for (size_t i = 0; i < z.size(); ++i) w[i] = z[static_cast<size_t>(sigma[i])];
  Vec out(n + 1);
  out << to.packAsIs(w, y(n - 1)), y(n);
  return out;
}

// Border k of `to` for border `k` of `from`: a metronome's threshold goes with the metronome.
int exchangedBorder(const SlowFlowProblem& from, const SlowFlowProblem& to,
                    const std::vector<int>& sigma, int k) {
  const int i = k < 0 ? -1 : from.metronomeOf(k);
  if (i < 0) return k;
  const int carrier = exchangedReference(sigma, i);  // the metronome that has i's state
  const int m = from.system().n / 2;                 // the thresholds come first, one each
  for (int b = 0; b < m; ++b)
    if (to.metronomeOf(b) == carrier) return b;
  return k;  // (not reached: exchanged metronomes are both unlocked)
}

BranchPoint exchangedPoint(const SlowFlowProblem& from, const SlowFlowProblem& to,
                           const std::vector<int>& sigma, const BranchPoint& q) {
  BranchPoint out = q;
  out.y = exchanged(from, to, sigma, q.y);
  out.tangent = exchanged(from, to, sigma, q.tangent);
  for (size_t k = 0; k < q.region.size(); ++k)
    out.region[static_cast<size_t>(exchangedBorder(from, to, sigma, static_cast<int>(k)))] =
        q.region[k];
  out.on_border = exchangedBorder(from, to, sigma, q.on_border);
  return out;
}

}  // namespace

std::vector<int> exchangeClasses(const ParamsAt& params, double from, double to) {
  std::vector<ScaledParams> at = {params(from), params(to)};
  for (int k = 1; k <= kSamples; ++k) at.push_back(params(from + (to - from) * k / (kSamples + 1)));
  const int n = static_cast<int>(at.front().nu.size());
  std::vector<int> classes(n);
  for (int i = 0; i < n; ++i) {
    classes[i] = i;
    for (int j = 0; j < i && classes[i] == i; ++j)
      if (std::all_of(at.begin(), at.end(),
                      [&](const ScaledParams& a) { return sameMetronome(a, i, j); }))
        classes[i] = classes[j];
  }
  return classes;
}

std::optional<std::vector<int>> exchangeOf(const std::vector<Cd>& copy, const std::vector<Cd>& z,
                                           const std::vector<int>& classes, double tolerance) {
  if (copy.size() != z.size() || copy.empty()) return std::nullopt;
  size_t a = 0;  // the copy's largest amplitude fixes the rotation
  for (size_t i = 1; i < copy.size(); ++i)
    if (std::abs(copy[i]) > std::abs(copy[a])) a = i;
  if (std::abs(copy[a]) == 0) return std::nullopt;
  std::vector<Cd> tried;  // one try per distinct z_j (equal ones give the same exchange)
  for (size_t j = 0; j < z.size(); ++j) {
    if (classes[j] != classes[a] || std::abs(std::abs(z[j]) - std::abs(copy[a])) > tolerance ||
        std::any_of(tried.begin(), tried.end(),
                    [&](Cd t) { return std::abs(t - z[j]) <= tolerance; }))
      continue;
    tried.push_back(z[j]);
    const Cd turn = z[j] / std::abs(z[j]) * std::conj(copy[a] / std::abs(copy[a]));
    if (auto sigma = matched(copy, z, classes, turn, tolerance)) return sigma;
  }
  return std::nullopt;
}

int exchangedReference(const std::vector<int>& sigma, int reference) {
  return static_cast<int>(std::find(sigma.begin(), sigma.end(), reference) - sigma.begin());
}

std::vector<Branch> exchangedBranches(const SlowFlowProblem& from, const SlowFlowProblem& to,
                                      const std::vector<int>& sigma,
                                      const std::vector<Branch>& branches) {
  std::vector<Branch> out = branches;
  for (Branch& b : out) {
    for (BranchPoint& q : b.points) q = exchangedPoint(from, to, sigma, q);
    for (Bifurcation& e : b.special) {
      e.point = exchangedPoint(from, to, sigma, e.point);
      e.border = exchangedBorder(from, to, sigma, e.border);
    }
    const int n = from.system().n;
    for (FamilyExtent& e : b.extent)
      for (Vec& x : e.members) {
        Vec y(n + 1);
        y << x, 0.0;
        x = exchanged(from, to, sigma, y).head(n);
      }
  }
  return out;
}

}  // namespace metrosync::continuation
