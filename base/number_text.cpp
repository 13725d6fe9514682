#include "base/number_text.h"

#include <fmt/format.h>  // FMT_HEADER_ONLY (CMakeLists.txt: fmt::fmt-header-only)

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace metrosync {

namespace {

constexpr std::uint64_t kPow10[] = {1ull,
                                    10ull,
                                    100ull,
                                    1000ull,
                                    10000ull,
                                    100000ull,
                                    1000000ull,
                                    10000000ull,
                                    100000000ull,
                                    1000000000ull,
                                    10000000000ull,
                                    100000000000ull,
                                    1000000000000ull,
                                    10000000000000ull,
                                    100000000000000ull,
                                    1000000000000000ull,
                                    10000000000000000ull,
                                    100000000000000000ull,
                                    1000000000000000000ull};

// v / 10^e for 0 < e <= 16 (the digits dropped from Dragonbox's at most 17): a constant divisor
// in each case, which the compiler turns into a multiplication (a 64-bit division by a variable
// costs tens of cycles, once per number written)
std::uint64_t divPow10(std::uint64_t v, int e) {
  switch (e) {
    case 1:
      return v / 10ull;
    case 2:
      return v / 100ull;
    case 3:
      return v / 1000ull;
    case 4:
      return v / 10000ull;
    case 5:
      return v / 100000ull;
    case 6:
      return v / 1000000ull;
    case 7:
      return v / 10000000ull;
    case 8:
      return v / 100000000ull;
    case 9:
      return v / 1000000000ull;
    case 10:
      return v / 10000000000ull;
    case 11:
      return v / 100000000000ull;
    case 12:
      return v / 1000000000000ull;
    case 13:
      return v / 10000000000000ull;
    case 14:
      return v / 100000000000000ull;
    case 15:
      return v / 1000000000000000ull;
    case 16:
      return v / 10000000000000000ull;
    default:
      return v / kPow10[e];
  }
}

// decimal digits of v > 0: log10 from the bit length (1233 / 4096 ~ log10(2)), then one compare
int digitCount(std::uint64_t v) {
  const int bits = 64 - __builtin_clzll(v);
  const int d = (bits * 1233) >> 12;
  return d + (v >= kPow10[d] ? 1 : 0);
}

// the two digits of every number below 100, for writing digits two at a time
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// the 8 digits of n < 10^8, leading zeros kept, into out[0..8): 32-bit arithmetic throughout
void writeEightDigits(std::uint32_t n, char* out) {
  const std::uint32_t high = n / 10000, low = n - 10000 * high;
  const std::uint32_t a = high / 100, b = high - 100 * a, c = low / 100, d = low - 100 * c;
  std::memcpy(out, kDigitPairs + 2 * a, 2);
  std::memcpy(out + 2, kDigitPairs + 2 * b, 2);
  std::memcpy(out + 4, kDigitPairs + 2 * c, 2);
  std::memcpy(out + 6, kDigitPairs + 2 * d, 2);
}

// the k digits of s into out[0..k): the last eight at a time, the rest two at a time
void writeDigits(std::uint64_t s, int k, char* out) {
  while (k > 8) {
    const std::uint64_t top = s / 100000000;
    writeEightDigits(static_cast<std::uint32_t>(s - 100000000 * top), out + k - 8);
    s = top;
    k -= 8;
  }
  auto n = static_cast<std::uint32_t>(s);  // at most 8 digits
  int i = k;
  while (i >= 2) {
    const std::uint32_t q = n / 100;
    std::memcpy(out + i - 2, kDigitPairs + 2 * (n - 100 * q), 2);
    n = q;
    i -= 2;
  }
  if (i == 1) out[0] = static_cast<char>('0' + n);
}

// The digits (d <= 15 of them, no trailing zero; the buffer readable to 32 characters) laid out
// as printf's %.<p>g lays out a value whose first digit has the decimal exponent x. The digits are
// moved 16 at a time (copies of a constant size, inlined): out must have kMaxGeneralChars of room,
// and what lies past the returned end is scratch.
char* layoutGeneral(bool negative, const char* digits, int d, int x, int p, char* out) {
  constexpr size_t kMove = 16;
  if (negative) *out++ = '-';
  if (x < -4 || x >= p) {  // %e
    *out++ = digits[0];
    if (d > 1) {
      *out++ = '.';
      std::memcpy(out, digits + 1, kMove);
      out += d - 1;
    }
    *out++ = 'e';
    *out++ = x < 0 ? '-' : '+';
    int ax = x < 0 ? -x : x;
    if (ax >= 100) {
      *out++ = static_cast<char>('0' + ax / 100);
      ax %= 100;
    }
    *out++ = static_cast<char>('0' + ax / 10);
    *out++ = static_cast<char>('0' + ax % 10);
    return out;
  }
  if (x < 0) {  // 0.000ddd
    *out++ = '0';
    *out++ = '.';
    for (int i = 0; i < -x - 1; ++i) *out++ = '0';
    std::memcpy(out, digits, kMove);
    return out + d;
  }
  std::memcpy(out, digits, kMove);
  if (d <= x + 1) {  // an integer: ddd000
    out += d;
    for (int i = d; i <= x; ++i) *out++ = '0';
    return out;
  }
  out[x + 1] = '.';  // ddd.ddd
  std::memcpy(out + x + 2, digits + x + 1, kMove);
  return out + d + 1;
}

char* toCharsGeneral(double v, int precision, char* out, char* end) {
  return std::to_chars(out, end, v, std::chars_format::general, precision).ptr;
}

// 10^k for k = 0 .. 22: every one a double exactly
constexpr double kPow10Double[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                   1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// a = |v| 10^k exactly, as hi + lo (k <= 22: 10^k is a double, the product's error is a double)
struct Scaled {
  double hi, lo;
};
Scaled scaleExactly(double a, int k) {
  const double p = kPow10Double[k];
  const double hi = a * p;
  return {hi, std::fma(a, p, -hi)};
}

// s / 10^z with the trailing zeros z dropped (s > 0), and k reduced by z
std::uint64_t dropTrailingZeros(std::uint64_t s, int& k) {
  if (s % 10 != 0) return s;          // the usual case
  for (const int z : {8, 4, 2, 1}) {  // at most 15 zeros: in halving steps
    if (k > z && s % kPow10[z] == 0) {
      s /= kPow10[z];
      k -= z;
    }
  }
  return s;
}

// %.<p>g's p digits of a = |v| > 0 (p <= 15) without the shortest digits: a 10^k for the k that
// puts a's first digit at 10^(p-1), exact as a double-double (k from 0 to 22, where 10^k is a
// double: |a| from about 10^(p-23) to 10^(p-1)), rounded to the nearest integer unless its
// fraction lies within 1e-9 of a half (the fraction's own rounding error is below 1e-16): false
// then, and outside that range, for writeGeneral's other ways. s: the digits, x: the first one's
// decimal exponent.
bool scaledDigits(double a, int p, std::uint64_t& s, int& x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &a, sizeof a);
  const int e2 = static_cast<int>(bits >> 52) - 1023;  // a normal a in [2^e2, 2^(e2+1))
  x = (e2 * 78913) >> 18;  // floor(e2 log10 2): the exponent, or one below it
  int k = p - 1 - x;
  if (k < 1 || k > 22) return false;
  Scaled t = scaleExactly(a, k);
  if (t.hi >= kPow10Double[p]) {  // the first digit is at 10^(x+1) (or a rounds up to it)
    ++x;
    t = scaleExactly(a, --k);
  }
  const std::uint64_t floor_hi = static_cast<std::uint64_t>(t.hi);  // t.hi > 0
  const double whole = static_cast<double>(floor_hi);
  const double frac = (t.hi - whole) + t.lo;  // t.hi - whole is exact (t.hi < 10^15 < 2^53)
  constexpr double kDoubt = 1e-9;
  if (std::abs(frac - 0.5) <= kDoubt) return false;
  s = floor_hi + (frac > 0.5 ? 1 : 0);
  if (s == kPow10[p]) {  // 9.99.. rounded up to 10.0..
    s = kPow10[p - 1];
    ++x;
  }
  return s >= kPow10[p - 1];  // else a just below a power of ten: the shortest digits' way
}

}  // namespace

// Zero as printf writes it. For the rows' magnitudes (a first digit from about 10^(p-23) to
// 10^(p-2)), the p digits from |v| 10^k as an exact double-double (scaledDigits: about a third of
// the shortest digits' cost). Elsewhere, and where that rounds within 1e-9 of a half: the shortest
// decimal S that reads back as v (Dragonbox, through {fmt}) lies within 5 units of its last digit
// of v (its unit is at least a tenth of v's ulp, else a shorter one would do), so rounding S to p
// digits rounds v the same way unless the digits dropped are within that of a half: those few go
// to std::to_chars, as do p > 15 and subnormals (where the p-digit grid can be finer than the
// ulp), infinities and NaN.
char* writeGeneral(double v, int precision, char* out) {
  char* const end = out + kMaxGeneralChars;
  const int p = precision < 1 ? 1 : precision;
  // (subnormals too: their ulp is coarser than 15 digits, and S is no longer p digits of v)
  if (v == 0.0) {  // printf's "0" and "-0"
    char* o = out;
    if (std::signbit(v)) *o++ = '-';
    *o++ = '0';
    return o;
  }
  if (!(std::abs(v) >= std::numeric_limits<double>::min()) || !std::isfinite(v) || p > 15)
    return toCharsGeneral(v, p, out, end);
  std::uint64_t scaled = 0;
  int scaled_x = 0;
  if (scaledDigits(std::abs(v), p, scaled, scaled_x)) {
    int k = p;
    scaled = dropTrailingZeros(scaled, k);
    char digits[32];
    writeDigits(scaled, k, digits);
    return layoutGeneral(v < 0, digits, k, scaled_x, p, out);
  }
  const auto dec = fmt::detail::dragonbox::to_decimal(std::abs(v));
  std::uint64_t s = dec.significand;
  int k = digitCount(s);
  int x = dec.exponent + k - 1;  // the first digit's exponent
  if (k > p) {
    const std::uint64_t unit = kPow10[k - p], half = unit / 2, q = divPow10(s, k - p),
                        r = s - q * unit;
    constexpr std::uint64_t kDoubt = 6;  // > 5 units of S's last digit
    if (r + kDoubt >= half && r <= half + kDoubt) return toCharsGeneral(v, p, out, end);
    s = q + (r > half ? 1 : 0);
    k = p;
    if (s == kPow10[p]) {  // 9.99.. rounded up to 10.0..
      s = kPow10[p - 1];
      ++x;
    }
  }
  while (k > 1 && s % 10 == 0) {  // %g drops trailing zeros
    s /= 10;
    --k;
  }
  char digits[32];
  writeDigits(s, k, digits);
  return layoutGeneral(v < 0, digits, k, x, p, out);
}

}  // namespace metrosync
