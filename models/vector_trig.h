// sin and cos of many angles at once, through glibc's vector math library (libmvec): the
// equations of motion need sin and cos of every pendulum angle at every stage, and one vector call
// does 8 (AVX-512), 4 (AVX2) or 2 (SSE2) angles in about the time of one scalar sincos. The widest
// variant the CPU supports is chosen once, at the first call; libmvec's results are within 4 ulp
// of the scalar ones (measured: within 1 ulp on |x| < 2). Without glibc on x86-64, a scalar loop.
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

// s[i] = sin(x[i]), c[i] = cos(x[i]) for i < n; x, s and c may not overlap.
inline void sinCos(const double* x, double* s, double* c, int n) {
  if (n >= kVectorTrigMin) return vectorSinCos(x, s, c, n);
  scalarSinCos(x, s, c, n);
}

// The widest vector variant in use: "avx512", "avx2", "sse2" or "scalar" (for benchmarks and the
// build report).
const char* sinCosVariant();

}  // namespace metrosync
