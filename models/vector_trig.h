// sin and cos of many angles at once: the equations of motion need sin and cos of every pendulum
// angle at every stage (2 N of them at N pendulums: the largest single cost of an evaluation).
//   - Angles a pendulum actually swings through (|x| <= kSmallAngle, 74 degrees) take the Taylor
//     polynomials of sin to x^19 and cos to x^20, two angles per SSE2 instruction, inlined: the
//     truncation is below 5e-18 (sin) and 3e-19 (cos) there, so the results are within 4 ulp of
//     glibc's (tests/models/test_vector_trig.cpp); about 100 instructions for two angles, where
//     glibc's sincos takes about 120 for one.
//   - Anything else (a pendulum thrown over the top, a huge or non-finite argument) goes through
//     glibc's vector math library (libmvec) from kVectorTrigMin angles on, 8 (AVX-512), 4 (AVX2)
//     or 2 (SSE2) at a time, the widest variant the CPU supports chosen at the first call (within
//     4 ulp of the scalar functions; measured within 1 ulp on |x| < 2), else the scalar functions.
// Every result is a function of its own angle only (not of the other angles in the call, nor of
// the instruction set), so mirror-image pendulums get mirror-image sines.
#pragma once

#include <cmath>

namespace metrosync {

// Below this many angles the scalar sincos is as fast (the direct engine at N = 2 ran 4% slower
// through libmvec's SSE2 variant), inlined here, with the scalar functions' bits.
constexpr int kVectorTrigMin = 4;

// the vector variant (any n: the tail that fills no vector goes through scalarSinCos)
void vectorSinCos(const double* x, double* s, double* c, int n);

inline void scalarSinCos(const double* x, double* s, double* c, int n) {
  for (int i = 0; i < n; ++i) {
    const double xi = x[i];  // one sincos call (s may alias x as far as the compiler knows)
    s[i] = std::sin(xi);
    c[i] = std::cos(xi);
  }
}

// The polynomials' domain: |x| <= 1.3 rad keeps cos >= 0.27, where the cancellation in
// 1 - x^2/2 + ... costs at most 2 ulp, and the truncation far below one.
constexpr double kSmallAngle = 1.3;

namespace trig_detail {

typedef double Pair __attribute__((vector_size(16)));  // two angles: one SSE2 register

// sin and cos of two angles with |x| <= kSmallAngle: Taylor to x^19 and x^20 as polynomials of
// degree 8 in u = x^2, summed by Estrin's scheme (pairs of terms, then pairs of pairs with u^2
// and u^4) rather than by Horner's rule. Horner's rule is one chain of 8 multiply-adds per
// polynomial; Estrin's is 4 deep. The right-hand side waits on these sines at every stage (the
// next stage's state is made from this one's derivative), so the chain's latency is the
// evaluation's. Measured against Horner's rule (metrosync_engine_probe, medians of 11 alternating
// runs, 2 cores with nothing else running): the bench scenes 1.03-1.16x faster (peer-n2 1.05x,
// suppression 1.16x) for 0.4% (N = 2) and 0.8% (N = 8) more instructions. The same accuracy: within
// 2 ulp of glibc over 2e6 random angles (tests/models/test_vector_trig.cpp).
inline void smallSinCos(Pair x, Pair& s, Pair& c) {
  const Pair u = x * x;
  const Pair u2 = u * u;
  const Pair u4 = u2 * u2;
  // sin x = x - x u ps(u), ps(u) = 1/3! - u/5! + u^2/7! - ... + u^8/19!
  const Pair s01 = 1.0 / 6.0 - u * (1.0 / 120.0);                          // 1/3!, 1/5!
  const Pair s23 = 1.0 / 5040.0 - u * (1.0 / 362880.0);                    // 1/7!, 1/9!
  const Pair s45 = 1.0 / 39916800.0 - u * (1.0 / 6227020800.0);            // 1/11!, 1/13!
  const Pair s67 = 1.0 / 1307674368000.0 - u * (1.0 / 355687428096000.0);  // 1/15!, 1/17!
  const Pair s8 = u4 * (1.0 / 121645100408832000.0);                       // 1/19!
  const Pair ps = (s01 + u2 * s23) + u4 * ((s45 + u2 * s67) + s8);
  s = x - x * u * ps;
  // cos x = 1 - u/2 + u^2 pc(u), pc(u) = 1/4! - u/6! + u^2/8! - ... + u^8/20!
  const Pair c01 = 1.0 / 24.0 - u * (1.0 / 720.0);                           // 1/4!, 1/6!
  const Pair c23 = 1.0 / 40320.0 - u * (1.0 / 3628800.0);                    // 1/8!, 1/10!
  const Pair c45 = 1.0 / 479001600.0 - u * (1.0 / 87178291200.0);            // 1/12!, 1/14!
  const Pair c67 = 1.0 / 20922789888000.0 - u * (1.0 / 6402373705728000.0);  // 1/16!, 1/18!
  const Pair c8 = u4 * (1.0 / 2432902008176640000.0);                        // 1/20!
  const Pair pc = (c01 + u2 * c23) + u4 * ((c45 + u2 * c67) + c8);
  c = 1.0 - 0.5 * u + u2 * pc;
}

// every |x[i]| <= kSmallAngle (false for a NaN)
inline bool allSmall(const double* x, int n) {
  bool small = true;
  for (int i = 0; i < n; ++i) small &= std::abs(x[i]) <= kSmallAngle;
  return small;
}

}  // namespace trig_detail

// The polynomials on every angle when all are small; false (nothing written) otherwise.
inline bool smallAngleSinCos(const double* x, double* s, double* c, int n) {
  using trig_detail::Pair;
  if (!trig_detail::allSmall(x, n)) return false;
  int i = 0;
  for (; i + 2 <= n; i += 2) {
    Pair v, sv, cv;
    __builtin_memcpy(&v, x + i, sizeof v);
    trig_detail::smallSinCos(v, sv, cv);
    __builtin_memcpy(s + i, &sv, sizeof sv);
    __builtin_memcpy(c + i, &cv, sizeof cv);
  }
  if (i < n) {  // the last odd angle in lane 0 (the same operations, so the same bits)
    Pair v = {x[i], 0.0}, sv, cv;
    trig_detail::smallSinCos(v, sv, cv);
    s[i] = sv[0];
    c[i] = cv[0];
  }
  return true;
}

// s[i] = sin(x[i]), c[i] = cos(x[i]) for i < n; x, s and c may not overlap.
inline void sinCos(const double* x, double* s, double* c, int n) {
  if (smallAngleSinCos(x, s, c, n)) return;
  if (n >= kVectorTrigMin) return vectorSinCos(x, s, c, n);
  scalarSinCos(x, s, c, n);
}

// The widest vector variant in use: "avx512", "avx2", "sse2" or "scalar" (for benchmarks and the
// build report).
const char* sinCosVariant();

}  // namespace metrosync
