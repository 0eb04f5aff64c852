// Integer-only sin/cos, atan2 and angle wrapping on Q16.16 raw values. See detail/Trig.h.
//
// Internal formats: "Qn" means value * 2^n. Polynomials run in unsigned Q32 on non-negative
// arguments (signs are restored afterwards), with every product rounded to nearest, so the
// internal error stays around 2^-32 and the final rounding to Q16.16 is almost always correct.
// Polynomial coefficients come from Chebyshev fits (mpmath, 40 digits) rounded to Q32; the
// approximation error of each fit is below 2^-36 on its interval.
#include "lockbox/fixed/detail/Trig.h"

#include <bit>
#include <cstdint>

namespace lockbox::detail {
namespace {

constexpr uint64_t kHalfQ32 = uint64_t{1} << 31;

// Round-to-nearest Q32 x Q32 -> Q32 product of non-negative values below 2^32 (no overflow:
// (2^32 - 1)^2 + 2^31 < 2^64).
constexpr uint64_t MulQ32(uint64_t a, uint64_t b) noexcept { return (a * b + kHalfQ32) >> 32; }
// Truncating variant for the inner Horner steps, whose error is damped by later factors of z.
constexpr uint64_t MulQ32Floor(uint64_t a, uint64_t b) noexcept { return (a * b) >> 32; }

// ---- sin / cos -------------------------------------------------------------------------------

// round(2/pi * 2^32): k = round(|x| * 2/pi) from the raw angle.
constexpr uint64_t kTwoOverPiQ32 = 2734261102u;
// pi/2 = (kHalfPiQ47 + kHalfPiLoQ79 / 2^32) / 2^47 with error < 2^-80.
constexpr int64_t kHalfPiQ47 = 221069929750889;
constexpr int64_t kHalfPiLoQ79 = -1036729146;

// sin r = r - r^3 P(z), cos r = 1 - z Q(z), z = r^2, |r| <= pi/4 + 2^-20. P and Q are
// Chebyshev (near-minimax) fits of (r - sin r) / r^3 and (1 - cos r) / z on z in [0, (pi/4)^2]
// (mpmath chebyfit, 40 digits), coefficients rounded to Q32. Approximation error: sin 2^-36.1,
// cos 2^-42.0 (absolute, radians), far below the Q32 rounding of the evaluation.
constexpr uint64_t kSinP0 = 715827883;  // ~1/3!
constexpr uint64_t kSinP1 = 35791388;   // ~1/5!
constexpr uint64_t kSinP2 = 852125;     // ~1/7!
constexpr uint64_t kSinP3 = 11704;      // ~1/9!
constexpr uint64_t kCosQ0 = 2147483648; // 1/2!
constexpr uint64_t kCosQ1 = 178956971;  // ~1/4!
constexpr uint64_t kCosQ2 = 5965231;    // ~1/6!
constexpr uint64_t kCosQ3 = 106515;     // ~1/8!
constexpr uint64_t kCosQ4 = 1170;       // ~1/10!

// ---- atan2 -----------------------------------------------------------------------------------

// Segment boundaries on t = min/max in [0, 1]: tan(pi/16) and tan(3pi/16) in Q32.
constexpr uint64_t kTanPi16Q32 = 854322113;
constexpr uint64_t kTan3Pi16Q32 = 2869805398u;
// Segment centres theta_j = 0, pi/8, pi/4: cos and sin in Q31, theta in Q40.
struct AtanSegment {
  uint64_t cos_q31;
  uint64_t sin_q31;
  int64_t theta_q40;
};
constexpr AtanSegment kAtanSegments[3] = {
    {uint64_t{1} << 31, 0, 0},
    {1984016189, 821806413, 431777206545},
    {1518500250, 1518500250, 863554413089},
};
constexpr int64_t kHalfPiQ40 = 1727108826179;
constexpr int64_t kPiQ40 = 3454217652358;
// atan u = u - u^3 A(z), z = u^2, |u| <= tan(pi/16) (+ a hair). A is a Chebyshev fit of
// (u - atan u) / u^3 on z in [0, tan^2(pi/16)], coefficients in Q32; error 2^-36.2.
constexpr uint64_t kAtanA0 = 1431655758;  // ~1/3
constexpr uint64_t kAtanA1 = 858987794;   // ~1/5
constexpr uint64_t kAtanA2 = 612846756;   // ~1/7
constexpr uint64_t kAtanA3 = 447688019;   // ~1/9

// ---- wrap ------------------------------------------------------------------------------------

// round(2^32 / (2 pi)): turns per raw unit in Q48.
constexpr int64_t kInvTwoPiQ48 = 683565276;

// |v| of an int32 as uint32 (exact for INT32_MIN).
constexpr uint32_t AbsU32(int32_t v) noexcept {
  return v < 0 ? 0u - static_cast<uint32_t>(v) : static_cast<uint32_t>(v);
}

}  // namespace

void SinCosRaw(int32_t angle, int32_t* s, int32_t* c) noexcept {
  const bool negative = angle < 0;
  const uint64_t ax = AbsU32(angle);  // |angle| raw, <= 2^31

  // Quadrant k = round(|x| / (pi/2)) (<= 20861). It may be off by one next to a boundary;
  // then |r| exceeds pi/4 by a hair, which the series tolerate.
  const uint64_t k = (ax * kTwoOverPiQ32 + (uint64_t{1} << 47)) >> 48;
  // r = |x| - k pi/2 in Q47, exact to ~2^-47: |x| << 31 < 2^63 and k * kHalfPiQ47 < 2^62.
  const int64_t ki = static_cast<int64_t>(k);
  const int64_t r47 = static_cast<int64_t>(ax << 31) - ki * kHalfPiQ47 - ((ki * kHalfPiLoQ79) >> 32);
  const bool r_negative = r47 < 0;
  const uint64_t ar47 = static_cast<uint64_t>(r_negative ? -r47 : r47);  // < 0.79 * 2^47

  // |r| in Q32 (rounded) and z = r^2 in Q32.
  const uint64_t r = (ar47 + (uint64_t{1} << 14)) >> 15;
  const uint64_t z = MulQ32(r, r);

  // sin |r|: the linear term stays in Q47, only the small r^3 term carries the Q32 error.
  uint64_t p = kSinP3;
  p = kSinP2 - MulQ32Floor(z, p);
  p = kSinP1 - MulQ32Floor(z, p);
  p = kSinP0 - MulQ32(z, p);
  const uint64_t r3p = MulQ32(MulQ32(r, z), p);  // r^3 P(z) in Q32, < 0.09
  const uint64_t sin47 = ar47 - (r3p << 15);
  const int32_t sin_raw = static_cast<int32_t>((sin47 + (uint64_t{1} << 30)) >> 31);

  // cos |r| in Q32 (value in [0.7, 1], so it needs 33 bits: fine in uint64).
  uint64_t q = kCosQ4;
  q = kCosQ3 - MulQ32Floor(z, q);
  q = kCosQ2 - MulQ32Floor(z, q);
  q = kCosQ1 - MulQ32Floor(z, q);
  q = kCosQ0 - MulQ32(z, q);
  const uint64_t cos32 = (uint64_t{1} << 32) - MulQ32(z, q);
  const int32_t cos_raw = static_cast<int32_t>((cos32 + (uint64_t{1} << 15)) >> 16);

  // Undo the reduction, branch-free (quadrants are unpredictable). A negative angle is
  // -(k pi/2 + r) = (-k) pi/2 + (-r): fold its sign into k and r. Then, with sr = +-sin|r|
  // (the sign of the effective r) and C = cos|r|, k pi/2 + r maps (sr, C) to
  //   k = 0: (sr, C),  1: (C, -sr),  2: (-sr, -C),  3: (-C, sr)   as (sin, cos).
  const int32_t neg_mask = negative ? -1 : 0;
  const uint32_t kq = (static_cast<uint32_t>(k) ^ static_cast<uint32_t>(neg_mask)) -
                      static_cast<uint32_t>(neg_mask);  // -k mod 2^32 when negative
  const int32_t r_mask = (r_negative ? -1 : 0) ^ neg_mask;
  const int32_t sr = (sin_raw ^ r_mask) - r_mask;
  const bool odd = (kq & 1u) != 0;
  const int32_t a = odd ? cos_raw : sr;
  const int32_t b = odd ? sr : cos_raw;
  // (v ^ m) - m negates v for m = -1 and keeps it for m = 0 (|v| <= 65536, no overflow).
  const int32_t sin_mask = -static_cast<int32_t>((kq >> 1) & 1u);
  const int32_t cos_mask = -static_cast<int32_t>(((kq + 1u) >> 1) & 1u);
  *s = (a ^ sin_mask) - sin_mask;
  *c = (b ^ cos_mask) - cos_mask;
}

int32_t Atan2Raw(int32_t y, int32_t x) noexcept {
  const uint32_t ay = AbsU32(y);
  const uint32_t ax = AbsU32(x);
  if ((ay | ax) == 0) return 0;

  // First octant: t = mn / mx in [0, 1]. Scale both so that mx has its top bit set; only the
  // ratio matters, and this keeps the division below exact to 2^-32 for tiny inputs too.
  const bool swapped = ay > ax;
  uint64_t mn = swapped ? ax : ay;
  uint64_t mx = swapped ? ay : ax;
  const int shift = std::countl_zero(static_cast<uint32_t>(mx));  // mx >= 1
  mn <<= shift;
  mx <<= shift;

  // Segment j with |atan(t) - theta_j| <= pi/16, then u = tan(atan(t) - theta_j) =
  // (mn cos - mx sin) / (mx cos + mn sin), |u| <= tan(pi/16) ~ 0.199.
  const uint64_t mn32 = mn << 32;
  const int j = (mn32 > mx * kTanPi16Q32 ? 1 : 0) + (mn32 > mx * kTan3Pi16Q32 ? 1 : 0);
  const AtanSegment& seg = kAtanSegments[j];
  const uint64_t pos = mn * seg.cos_q31;  // < 2^63
  const uint64_t neg = mx * seg.sin_q31;  // < 2^63
  const uint64_t den = mx * seg.cos_q31 + mn * seg.sin_q31;  // < 2^63.5, >= 2^61.5
  const bool u_negative = neg > pos;
  const uint64_t num = u_negative ? neg - pos : pos - neg;  // < 2^61.2
  const uint64_t den30 = (den + (uint64_t{1} << 29)) >> 30;  // >= 2^31.5
  const uint64_t u = ((num << 2) + (den30 >> 1)) / den30;  // |u| in Q32, < 0.2 * 2^32

  // atan |u| in Q32.
  const uint64_t z = MulQ32(u, u);
  uint64_t p = kAtanA3;
  p = kAtanA2 - MulQ32Floor(z, p);
  p = kAtanA1 - MulQ32Floor(z, p);
  p = kAtanA0 - MulQ32(z, p);
  const int64_t atan_u = static_cast<int64_t>(u - MulQ32(MulQ32(u, z), p));

  // Assemble in Q40: theta in [0, pi/4], then the octant, then the half plane.
  int64_t theta = seg.theta_q40 + (u_negative ? -atan_u : atan_u) * 256;
  if (swapped) theta = kHalfPiQ40 - theta;
  if (x < 0) theta = kPiQ40 - theta;
  const int32_t result = static_cast<int32_t>((theta + (int64_t{1} << 23)) >> 24);
  return y < 0 ? -result : result;
}

int32_t WrapAngleTurnsRaw(int32_t a, int32_t* turns) noexcept {
  // n ~ round(a / 2pi); |a * kInvTwoPiQ48| < 2^61. Exact value a - n 2pi in Q48 ("raw << 32"):
  // |n| <= 5215 so |n * kTwoPiQ48| < 2^63, and (a << 32) is in [-2^63, 2^63).
  const int64_t a64 = a;
  int64_t n = (a64 * kInvTwoPiQ48 + (int64_t{1} << 47)) >> 48;
  int64_t v = static_cast<int64_t>(static_cast<uint64_t>(a64) << 32) - n * kTwoPiQ48;
  // Make v lie in [-pi, pi). The estimate of n is at most one off. Comparisons against the
  // Q48 pi are exact decisions: |a - (2n + 1) pi| >= 2^-16.4 raw for every int32 a, far above
  // the 2^-20.6 raw carried error.
  if (v >= kPiQ48) {
    v -= kTwoPiQ48;
    ++n;
  } else if (v < -kPiQ48) {
    v += kTwoPiQ48;
    --n;
  }
  *turns = static_cast<int32_t>(n);
  // Round to nearest raw. No true value lies within 2^-13.9 raw of a half-integer, so this
  // equals the rounding of the exact value (half-up is never actually exercised).
  return static_cast<int32_t>((v + (int64_t{1} << 31)) >> 32);
}

int32_t WrapAngleRaw(int32_t a) noexcept {
  int32_t turns = 0;
  return WrapAngleTurnsRaw(a, &turns);
}

}  // namespace lockbox::detail
