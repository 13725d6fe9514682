// Basin stability (Menck et al., Nature Physics 9, 89 (2013)): how likely each regime is from
// random starts. `metrosync basin RIG --random KEY=FROM:TO ... --samples S --seed N` draws S
// starts uniformly, runs each as a sweep point (tools/cli/sweep.h), and reports the fraction of
// each regime with its 95% Wilson interval. This file owns the drawing and the statistics;
// tools/report/basin_files.h writes basin.csv and basin.json, tools/cli/basin.cpp runs.
//
//   draw     sample k's values depend only on (seed, k) (a SplitMix64 stream seeded from both),
//            not on --jobs nor on the order the samples run in; value = FROM + u (TO - FROM),
//            u uniform in [0, 1) with 53 random bits. A phase key (last segment phi or psi; not a
//            pendulum's start.angle, which must stay inside (-pi, pi)) is drawn on the circle: the
//            arc from FROM counter-clockwise to TO (the whole circle when TO - FROM is a nonzero
//            multiple of 2 pi), wrapped to [0, 2 pi).
//   Wilson   p = k/n, z = 1.959963984540054 (the 97.5% normal quantile):
//            centre = (p + z^2/(2n)) / (1 + z^2/n),
//            half   = z / (1 + z^2/n) * sqrt(p (1 - p) / n + z^2 / (4 n^2)).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace metrosync {

// One --random KEY=FROM:TO.
struct RandomKey {
  std::string key;
  std::string spec;  // FROM:TO as given
  double from = 0.0, to = 0.0;
  bool angle = false;  // drawn on the circle, wrapped to [0, 2 pi)
};

// "KEY=FROM:TO" (numbers or multiples of pi, as --vary); throws SweepInputError (sweep.h) saying
// what is wrong: no '=', not two numbers, FROM >= TO for a key that is not an angle. KEY is kept
// as written (the command resolves it, yaml/rig_loader.h); `phase`: it is drawn on the circle
// (isPhaseName of its last segment).
RandomKey parseRandom(const std::string& text, bool phase);

// Is a key's last segment a phase, drawn on the circle (phi or psi)?
bool isPhaseName(const std::string& last_segment);

// The value of `key` in sample `sample` for `seed`, key number `which` of the draw.
double drawValue(const RandomKey& key, std::uint64_t seed, long sample, size_t which);
// All the keys' values of one sample, in order.
std::vector<double> drawSample(const std::vector<RandomKey>& keys, std::uint64_t seed, long sample);

// A uniform number in [0, 1) for (seed, sample, which), 53 random bits.
double basinUniform(std::uint64_t seed, long sample, size_t which);

// The 95% Wilson score interval of k successes in n trials (n > 0).
struct WilsonInterval {
  double lo = 0.0, hi = 1.0;
};
WilsonInterval wilsonInterval(long k, long n, double z = 1.959963984540054);

// The count and fraction of each regime among n samples, with its interval.
struct RegimeFraction {
  std::string regime;
  long count = 0;
  double fraction = 0.0;
  WilsonInterval ci;
};
// `regimes` (one per sample) -> one entry per regime present, most frequent first (ties by name).
std::vector<RegimeFraction> regimeFractions(const std::vector<std::string>& regimes);
// ... from each regime's count of samples (a fixed-size tally, whatever the number of samples).
std::vector<RegimeFraction> regimeFractions(const std::map<std::string, long>& count);

}  // namespace metrosync
