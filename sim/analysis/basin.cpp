#include "sim/analysis/basin.h"

#include <algorithm>
#include <cmath>

#include "base/constants.h"
#include "sim/analysis/sweep.h"

namespace metrosync {

namespace {

// Arcs shorter than this (rad) count as a whole circle when TO - FROM is a multiple of 2 pi.
constexpr double kWholeCircleTolerance = 1e-12;

// SplitMix64 (Steele, Lea, Flood 2014): a fixed, portable generator (std:: distributions are not
// the same on every standard library).
std::uint64_t splitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

}  // namespace

bool isPhaseName(const std::string& last_segment) {
  return last_segment == "phi" || last_segment == "psi";
}

RandomKey parseRandom(const std::string& text, bool phase) {
  const std::string usage =
      "--random " + text + ": expected KEY=FROM:TO (e.g. metronomes.0.start.phi=0:2pi)";
  const size_t eq = text.find('=');
  if (eq == std::string::npos) throw SweepInputError(usage);
  RandomKey r;
  r.key = trimmed(text.substr(0, eq));
  r.spec = text.substr(eq + 1);
  if (r.key.empty() || r.key.find_first_of(" \t:=") != std::string::npos)
    throw SweepInputError(usage + ": no key before '='");
  const size_t colon = r.spec.find(':');
  if (colon == std::string::npos || r.spec.find(':', colon + 1) != std::string::npos)
    throw SweepInputError(usage);
  try {
    r.from = parseSweepNumber(r.spec.substr(0, colon));
    r.to = parseSweepNumber(r.spec.substr(colon + 1));
  } catch (const SweepInputError& e) {
    throw SweepInputError("--random " + text + ": " + e.what());
  }
  r.angle = phase;
  if (!r.angle && !(r.from < r.to))
    throw SweepInputError("--random " + text + ": FROM must be below TO (got " +
                          sweepValueText(r.from) + " and " + sweepValueText(r.to) + ")");
  if (r.angle && r.from == r.to)
    throw SweepInputError("--random " + text + ": FROM = TO draws nothing; 0:2pi is the circle");
  return r;
}

double basinUniform(std::uint64_t seed, long sample, size_t which) {
  // one stream per (seed, sample): its state from both, the key number picks the draw
  std::uint64_t state = seed;
  std::uint64_t s = splitMix64(state) ^ static_cast<std::uint64_t>(sample);
  std::uint64_t x = 0;
  for (size_t k = 0; k <= which; ++k) x = splitMix64(s);
  return static_cast<double>(x >> 11) * 0x1.0p-53;
}

double drawValue(const RandomKey& key, std::uint64_t seed, long sample, size_t which) {
  const double u = basinUniform(seed, sample, which);
  if (!key.angle) return key.from + u * (key.to - key.from);
  double arc = std::fmod(key.to - key.from, kTwoPi);
  if (arc < 0) arc += kTwoPi;
  if (arc < kWholeCircleTolerance || kTwoPi - arc < kWholeCircleTolerance) arc = kTwoPi;
  return wrapToTwoPi(key.from + u * arc);
}

std::vector<double> drawSample(const std::vector<RandomKey>& keys, std::uint64_t seed,
                               long sample) {
  std::vector<double> v;
  for (size_t k = 0; k < keys.size(); ++k) v.push_back(drawValue(keys[k], seed, sample, k));
  return v;
}

WilsonInterval wilsonInterval(long k, long n, double z) {
  if (n <= 0) return {0.0, 1.0};
  const double nn = static_cast<double>(n);
  const double p = static_cast<double>(k) / nn;
  const double z2 = z * z;
  const double denom = 1.0 + z2 / nn;
  const double centre = (p + z2 / (2.0 * nn)) / denom;
  const double half = z / denom * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

std::vector<RegimeFraction> regimeFractions(const std::vector<std::string>& regimes) {
  std::map<std::string, long> count;
  for (const auto& r : regimes) ++count[r];
  return regimeFractions(count);
}

std::vector<RegimeFraction> regimeFractions(const std::map<std::string, long>& count) {
  std::vector<RegimeFraction> out;
  long n = 0;
  for (const auto& [name, k] : count) n += k;
  for (const auto& [name, k] : count)
    out.push_back({name, k, static_cast<double>(k) / static_cast<double>(n), wilsonInterval(k, n)});
  std::stable_sort(out.begin(), out.end(), [](const RegimeFraction& a, const RegimeFraction& b) {
    return a.count > b.count;
  });
  return out;
}

}  // namespace metrosync
