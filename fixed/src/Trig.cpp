// Integer-only sin/cos, atan2 and angle wrapping on Q16.16 raw values. See detail/Trig.h.
//
// Internal formats: "Qn" means value * 2^n. Everything is int64/uint64 (no __int128, no float).
// - sin/cos: exact reduction by pi/128 (pi/128 carried to 2^-73), a 256-entry Q62 table of
//   sin(j pi/128) and short series for the remainder; internal error ~2^-36 rad, so the final
//   rounding to Q16.16 is correct for all but ~1 in 4 million inputs (max error 0.500001 ULP).
// - atan2: octant reduction, one division to u = tan(theta - theta_j) in Q32 for the nearest of
//   3 segment centres, a degree-9 odd polynomial; internal error ~2^-32 rad (max 0.50003 ULP).
// - wrap: whole turns of 2pi carried to 2^-48 rad; provably exact decisions and one rounding.
// Polynomial coefficients come from Chebyshev fits (mpmath, 40 digits) rounded to Q32.
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
//
// |x| = k pi/128 + d with k = round(|x| 128/pi) and |d| <= pi/256 (+ a hair). Then
//   sin x = sin A + cos A sin d + sin A (cos d - 1),
//   cos x = cos A + cos A (cos d - 1) - sin A sin d,
// with A = k pi/128 from a 256-entry table (the whole circle, so no quadrant logic), and short
// series for the small d: sin d ~ d - c d^3 (c ~ 1/6, error < 2^-41.6), cos d - 1 = -d^2/2 +
// d^4/24 (error < 2^-47).

// round(128/pi * 2^27): k = round(|x| * 128/pi) = (|x| * kStepsPerRawQ43 + 2^42) >> 43.
constexpr uint64_t kStepsPerRawQ43 = 5468522205u;
// pi/128 = (kStepQ40 + kStepLoQ72 / 2^32) / 2^40, error < 2^-73.
constexpr int64_t kStepQ40 = 26986075409;
constexpr int64_t kStepLoQ72 = 189141414;
// sin d ~ d - c d^3 with c slightly below 1/6 (best uniform fit on |d| <= pi/256 with the d^5
// term folded in): error 2^-41.6 instead of 2^-38.6 for c = 1/6. round(c * 2^32).
constexpr int64_t kSixthQ32 = 715823193;
constexpr int64_t kTwentyFourthQ32 = 178956971;  // round(2^32 / 24)

// kSinTableQ62[j] = round(sin(j pi/128) * 2^62), j = 0..255; cos(j pi/128) = entry (j + 64) & 255.
// Generated with mpmath at 300-bit precision. Every entry is exercised by thousands of inputs in
// tests/fixed/heavy/trig_exhaustive_test.cpp (and by the sweeps in tests/fixed/trig_test.cpp).
constexpr int64_t kSinTableQ62[256] = {
    0,
    113176440454146016,
    226284707652502141,
    339256669404298611,
    452024275624069880,
    564519599322481549,
    676674877523008785,
    788422552079819562,
    899695310372275547,
    1010426125851537790,
    1120548298414853464,
    1229995494583203681,
    1338701787458110889,
    1446601696433537347,
    1553630226638953726,
    1659722908089818799,
    1764815834521887442,
    1868845701885954606,
    1971749846479847467,
    2073466282694696471,
    2173933740352748318,
    2273091701614230011,
    2370880437431032621,
    2467241043525256456,
    2562115475870945497,
    2655446585657638225,
    2747178153714674114,
    2837254924375519865,
    2925622638761716784,
    3012228067466400296,
    3097019042617704261,
    3179944489302736311,
    3260954456333195553,
    3340000146334100615,
    3417033945137503676,
    3492009450463484836,
    3564881499871150442,
    3635606197962798751,
    3704140942824866152,
    3770444451689726907,
    3834476785802888710,
    3896199374480604983,
    3955575038343412514,
    4012568011711599423,
    4067143964149113252,
    4119270021142931949,
    4168914783905441250,
    4216048348287890265,
    4260642322793532497,
    4302669845679601858,
    4342105601137822079,
    4378925834543703005,
    4413108366765438139,
    4444632607523784314,
    4473479567794875989,
    4499631871248503178,
    4523073764714963030,
    4543791127674180203,
    4561771480761380163,
    4577003993284191887,
    4589479489746651964,
    4599190455376180266,
    4606131040650197959,
    4610297064819661174,
    4611686018427387904,
    4610297064819661174,
    4606131040650197959,
    4599190455376180266,
    4589479489746651964,
    4577003993284191887,
    4561771480761380163,
    4543791127674180203,
    4523073764714963030,
    4499631871248503178,
    4473479567794875989,
    4444632607523784314,
    4413108366765438139,
    4378925834543703005,
    4342105601137822079,
    4302669845679601858,
    4260642322793532497,
    4216048348287890265,
    4168914783905441250,
    4119270021142931949,
    4067143964149113252,
    4012568011711599423,
    3955575038343412514,
    3896199374480604983,
    3834476785802888710,
    3770444451689726907,
    3704140942824866152,
    3635606197962798751,
    3564881499871150442,
    3492009450463484836,
    3417033945137503676,
    3340000146334100615,
    3260954456333195553,
    3179944489302736311,
    3097019042617704261,
    3012228067466400296,
    2925622638761716784,
    2837254924375519865,
    2747178153714674114,
    2655446585657638225,
    2562115475870945497,
    2467241043525256456,
    2370880437431032621,
    2273091701614230011,
    2173933740352748318,
    2073466282694696471,
    1971749846479847467,
    1868845701885954606,
    1764815834521887442,
    1659722908089818799,
    1553630226638953726,
    1446601696433537347,
    1338701787458110889,
    1229995494583203681,
    1120548298414853464,
    1010426125851537790,
    899695310372275547,
    788422552079819562,
    676674877523008785,
    564519599322481549,
    452024275624069880,
    339256669404298611,
    226284707652502141,
    113176440454146016,
    0,
    -113176440454146016,
    -226284707652502141,
    -339256669404298611,
    -452024275624069880,
    -564519599322481549,
    -676674877523008785,
    -788422552079819562,
    -899695310372275547,
    -1010426125851537790,
    -1120548298414853464,
    -1229995494583203681,
    -1338701787458110889,
    -1446601696433537347,
    -1553630226638953726,
    -1659722908089818799,
    -1764815834521887442,
    -1868845701885954606,
    -1971749846479847467,
    -2073466282694696471,
    -2173933740352748318,
    -2273091701614230011,
    -2370880437431032621,
    -2467241043525256456,
    -2562115475870945497,
    -2655446585657638225,
    -2747178153714674114,
    -2837254924375519865,
    -2925622638761716784,
    -3012228067466400296,
    -3097019042617704261,
    -3179944489302736311,
    -3260954456333195553,
    -3340000146334100615,
    -3417033945137503676,
    -3492009450463484836,
    -3564881499871150442,
    -3635606197962798751,
    -3704140942824866152,
    -3770444451689726907,
    -3834476785802888710,
    -3896199374480604983,
    -3955575038343412514,
    -4012568011711599423,
    -4067143964149113252,
    -4119270021142931949,
    -4168914783905441250,
    -4216048348287890265,
    -4260642322793532497,
    -4302669845679601858,
    -4342105601137822079,
    -4378925834543703005,
    -4413108366765438139,
    -4444632607523784314,
    -4473479567794875989,
    -4499631871248503178,
    -4523073764714963030,
    -4543791127674180203,
    -4561771480761380163,
    -4577003993284191887,
    -4589479489746651964,
    -4599190455376180266,
    -4606131040650197959,
    -4610297064819661174,
    -4611686018427387904,
    -4610297064819661174,
    -4606131040650197959,
    -4599190455376180266,
    -4589479489746651964,
    -4577003993284191887,
    -4561771480761380163,
    -4543791127674180203,
    -4523073764714963030,
    -4499631871248503178,
    -4473479567794875989,
    -4444632607523784314,
    -4413108366765438139,
    -4378925834543703005,
    -4342105601137822079,
    -4302669845679601858,
    -4260642322793532497,
    -4216048348287890265,
    -4168914783905441250,
    -4119270021142931949,
    -4067143964149113252,
    -4012568011711599423,
    -3955575038343412514,
    -3896199374480604983,
    -3834476785802888710,
    -3770444451689726907,
    -3704140942824866152,
    -3635606197962798751,
    -3564881499871150442,
    -3492009450463484836,
    -3417033945137503676,
    -3340000146334100615,
    -3260954456333195553,
    -3179944489302736311,
    -3097019042617704261,
    -3012228067466400296,
    -2925622638761716784,
    -2837254924375519865,
    -2747178153714674114,
    -2655446585657638225,
    -2562115475870945497,
    -2467241043525256456,
    -2370880437431032621,
    -2273091701614230011,
    -2173933740352748318,
    -2073466282694696471,
    -1971749846479847467,
    -1868845701885954606,
    -1764815834521887442,
    -1659722908089818799,
    -1553630226638953726,
    -1446601696433537347,
    -1338701787458110889,
    -1229995494583203681,
    -1120548298414853464,
    -1010426125851537790,
    -899695310372275547,
    -788422552079819562,
    -676674877523008785,
    -564519599322481549,
    -452024275624069880,
    -339256669404298611,
    -226284707652502141,
    -113176440454146016,
};

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

    // k may be one off next to a rounding boundary: then |d| exceeds pi/256 by < 2^-20, which
    // the series tolerate. ax * kStepsPerRawQ43 < 2^63.35; k < 2^20.4.
    const uint64_t k = (ax * kStepsPerRawQ43 + (uint64_t{1} << 42)) >> 43;
    // d = |x| - k pi/128, exact to 2^-40: |x| in Q40 is ax << 24 < 2^55; k * kStepQ40 < 2^55.
    const int64_t ki = static_cast<int64_t>(k);
    const int64_t d40 = static_cast<int64_t>(ax << 24) - ki * kStepQ40 - ((ki * kStepLoQ72) >> 32);
    const int64_t d = (d40 + 4) >> 3;  // Q37, |d| < 2^30.7

    const int64_t d2 = (d * d) >> 37;                                            // d^2 in Q37, < 2^24.3
    const int64_t d3 = (d * d2) >> 37;                                           // d^3 in Q37 (signed)
    const int64_t d4 = (d2 * d2) >> 37;                                          // d^4 in Q37
    const int64_t sin_d = d - ((d3 * kSixthQ32) >> 32);                          // Q37
    const int64_t cos_d_m1 = ((d4 * kTwentyFourthQ32) >> 32) - ((d * d) >> 38);  // Q37, <= 0

    const uint32_t j = static_cast<uint32_t>(k) & 255u;
    const int64_t sin_a = kSinTableQ62[j];
    const int64_t cos_a = kSinTableQ62[(j + 64u) & 255u];
    // Q31 copies for the products: |Q31| <= 2^31 times |Q37| < 2^30.7 stays below 2^62.
    const int64_t sin_a31 = (sin_a + (int64_t{1} << 30)) >> 31;
    const int64_t cos_a31 = (cos_a + (int64_t{1} << 30)) >> 31;
    // Sums in Q62; each result is a sine or cosine plus < 2^-35 of error, so |sum| < 2^62 + 2^28.
    const int64_t sin62 = sin_a + ((cos_a31 * sin_d) >> 6) + ((sin_a31 * cos_d_m1) >> 6);
    const int64_t cos62 = cos_a + ((cos_a31 * cos_d_m1) >> 6) - ((sin_a31 * sin_d) >> 6);
    const int32_t sin_raw = static_cast<int32_t>((sin62 + (int64_t{1} << 45)) >> 46);
    const int32_t cos_raw = static_cast<int32_t>((cos62 + (int64_t{1} << 45)) >> 46);
    *s = negative ? -sin_raw : sin_raw;
    *c = cos_raw;
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
    const uint64_t pos = mn * seg.cos_q31;                     // < 2^63
    const uint64_t neg = mx * seg.sin_q31;                     // < 2^63
    const uint64_t den = mx * seg.cos_q31 + mn * seg.sin_q31;  // < 2^63.5, >= 2^61.5
    const bool u_negative = neg > pos;
    const uint64_t num = u_negative ? neg - pos : pos - neg;   // < 2^61.2
    const uint64_t den30 = (den + (uint64_t{1} << 29)) >> 30;  // >= 2^31.5
    const uint64_t u = ((num << 2) + (den30 >> 1)) / den30;    // |u| in Q32, < 0.2 * 2^32

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
