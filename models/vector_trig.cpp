#include "models/vector_trig.h"

#include <cmath>

#if defined(__x86_64__) && defined(__GLIBC__) && !defined(METROSYNC_NO_LIBMVEC)
#define METROSYNC_LIBMVEC 1
#include <immintrin.h>
#endif

namespace metrosync {

#ifdef METROSYNC_LIBMVEC

// libmvec's entry points (the x86-64 vector function ABI: b = SSE2, d = AVX2, e = AVX-512), each
// declared and called only inside code compiled for its instruction set.
extern "C" __m128d _ZGVbN2v_sin(__m128d);
extern "C" __m128d _ZGVbN2v_cos(__m128d);

namespace {

// pairs through the SSE2 variant, a last odd angle through the scalar functions
void sse2SinCos(const double* x, double* s, double* c, int n) {
  int i = 0;
  for (; i + 2 <= n; i += 2) {
    const __m128d v = _mm_loadu_pd(x + i);
    _mm_storeu_pd(s + i, _ZGVbN2v_sin(v));
    _mm_storeu_pd(c + i, _ZGVbN2v_cos(v));
  }
  scalarSinCos(x + i, s + i, c + i, n - i);
}

}  // namespace

#pragma GCC push_options
#pragma GCC target("avx2,fma")
extern "C" __m256d _ZGVdN4v_sin(__m256d);
extern "C" __m256d _ZGVdN4v_cos(__m256d);

namespace {

void avx2SinCos(const double* x, double* s, double* c, int n) {
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m256d v = _mm256_loadu_pd(x + i);
    _mm256_storeu_pd(s + i, _ZGVdN4v_sin(v));
    _mm256_storeu_pd(c + i, _ZGVdN4v_cos(v));
  }
  scalarSinCos(x + i, s + i, c + i, n - i);  // the SSE2 variant is slower inside AVX code
}

}  // namespace
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx512f")
extern "C" __m512d _ZGVeN8v_sin(__m512d);
extern "C" __m512d _ZGVeN8v_cos(__m512d);

namespace {

void avx512SinCos(const double* x, double* s, double* c, int n) {
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m512d v = _mm512_loadu_pd(x + i);
    _mm512_storeu_pd(s + i, _ZGVeN8v_sin(v));
    _mm512_storeu_pd(c + i, _ZGVeN8v_cos(v));
  }
  avx2SinCos(x + i, s + i, c + i, n - i);
}

}  // namespace
#pragma GCC pop_options

namespace {

using SinCosFn = void (*)(const double*, double*, double*, int);

struct Variant {
  SinCosFn fn;
  const char* name;
};

Variant chooseVariant() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return {avx512SinCos, "avx512"};
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return {avx2SinCos, "avx2"};
  return {sse2SinCos, "sse2"};
}

const Variant& variant() {
  static const Variant v = chooseVariant();
  return v;
}

}  // namespace

void vectorSinCos(const double* x, double* s, double* c, int n) {
  variant().fn(x, s, c, n);
}

const char* sinCosVariant() {
  return variant().name;
}

#else

void vectorSinCos(const double* x, double* s, double* c, int n) {
  scalarSinCos(x, s, c, n);
}

const char* sinCosVariant() {
  return "scalar";
}

#endif

}  // namespace metrosync
