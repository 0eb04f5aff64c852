#pragma once
// 64-bit integer lanes (AVX2) that compute, four at a time, the very integers of the solver's
// scalar rows: a rounded Q32.32 product is formed exactly from 32 x 32-bit partial products of
// the magnitudes and rounded half away from zero, as Wide's operators round; sums are exact.
// Where the scalar row could saturate (and report an overflow) lanes cannot follow, so every
// value a lane loads or forms is bounded (kBoundBits); a caller writes back only the lanes no
// bound flagged and solves the rest with the scalar row. The rows that use them solve
// constraints of one colour, which write no body in common (dynamics/Colours.h), so four at
// once give what one after the other gives.
//
// Lanes need x86-64 with AVX2, checked once at run time; elsewhere the scalar rows run.
#include <cstdint>

#include "lockbox/dynamics/StepObserver.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define LOCKBOX_INTEGER_LANES 1
#include <immintrin.h>
#endif

namespace lockbox::lanes {

/// Whether the lanes may run (the default). Both paths give the same bits; tests switch them off
/// to compare.
bool Allowed() noexcept;
void Allow(bool allow) noexcept;

}  // namespace lockbox::lanes

#ifdef LOCKBOX_INTEGER_LANES
#define LOCKBOX_AVX2 __attribute__((target("avx2")))

namespace lockbox::lanes {

inline bool HasAvx2() noexcept {
    static const bool has = __builtin_cpu_supports("avx2") != 0;
    return has;
}

using Lanes = __m256i;

// Whether this machine has the lanes and they are allowed.
inline bool Usable() noexcept { return HasAvx2() && Allowed(); }

// One field of four rows as lanes (lane k from items[k], a pointer to row k).
#define LOCKBOX_LANES_OF(items, field)                                                                    \
    _mm256_set_epi64x(int64_t{(items)[3]->field}, int64_t{(items)[2]->field}, int64_t{(items)[1]->field}, \
                      int64_t{(items)[0]->field})

// Every value a lane loads or a product forms stays below 2^kBoundBits in magnitude. A row adds
// at most eight such terms into one sum, so no sum reaches 2^62, and no lane wraps where the
// scalar row would saturate.
constexpr int kBoundBits = 59;

// A lane value as magnitude and sign mask (all ones where negative).
struct Split {
    Lanes mag;
    Lanes neg;
};

LOCKBOX_AVX2 inline Lanes Zero() { return _mm256_setzero_si256(); }
LOCKBOX_AVX2 inline Lanes Add(Lanes a, Lanes b) { return _mm256_add_epi64(a, b); }
LOCKBOX_AVX2 inline Lanes Sub(Lanes a, Lanes b) { return _mm256_sub_epi64(a, b); }
LOCKBOX_AVX2 inline Lanes Neg(Lanes a) { return _mm256_sub_epi64(Zero(), a); }
LOCKBOX_AVX2 inline Lanes Max(Lanes a, Lanes b) { return _mm256_blendv_epi8(a, b, _mm256_cmpgt_epi64(b, a)); }
LOCKBOX_AVX2 inline Lanes Min(Lanes a, Lanes b) { return _mm256_blendv_epi8(a, b, _mm256_cmpgt_epi64(a, b)); }

LOCKBOX_AVX2 inline Split SplitSign(Lanes x) {
    const Lanes neg = _mm256_cmpgt_epi64(Zero(), x);
    return {_mm256_sub_epi64(_mm256_xor_si256(x, neg), neg), neg};
}
LOCKBOX_AVX2 inline Lanes WithSign(Lanes mag, Lanes neg) { return _mm256_sub_epi64(_mm256_xor_si256(mag, neg), neg); }
// -x as a split (a zero magnitude gives zero whatever its sign).
LOCKBOX_AVX2 inline Split Flip(const Split& s) { return {s.mag, _mm256_xor_si256(s.neg, _mm256_set1_epi64x(-1))}; }

// Whether a and b hold the same value in every lane.
LOCKBOX_AVX2 inline bool AllEqual(Lanes a, Lanes b) { return _mm256_movemask_epi8(_mm256_cmpeq_epi64(a, b)) == -1; }

// Marks the lanes where `bits` is non-zero.
LOCKBOX_AVX2 inline void Flag(Lanes& unsafe, Lanes bits) { unsafe = _mm256_or_si256(unsafe, bits); }
// The lanes no bound flagged (bit k: lane k), which their rows may write back.
LOCKBOX_AVX2 inline uint32_t Followed(Lanes unsafe) {
    return static_cast<uint32_t>(_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpeq_epi64(unsafe, Zero()))));
}
// Marks the lanes where |x| >= 2^kBoundBits (INT64_MIN included: its magnitude is 2^63).
LOCKBOX_AVX2 inline void Bound(Lanes& unsafe, Lanes x) {
    Flag(unsafe, _mm256_srli_epi64(SplitSign(x).mag, kBoundBits));
}

// Wide * Fixed (a Q32.32 raw times a Q16.16 raw, rounded by 2^16): with |w| = h 2^32 + l,
// round(|w| |f| / 2^16) = h |f| 2^16 + round(l |f| / 2^16), as h |f| 2^32 is a multiple of 2^16.
LOCKBOX_AVX2 inline Lanes MulWF(Lanes& unsafe, Lanes w, const Split& f) {
    const Split s = SplitSign(w);
    const Lanes hi = _mm256_mul_epu32(_mm256_srli_epi64(s.mag, 32), f.mag);
    const Lanes lo = _mm256_mul_epu32(s.mag, f.mag);
    // hi < 2^42 keeps the magnitude below 2^58 + 2^47.
    Flag(unsafe, _mm256_srli_epi64(hi, kBoundBits - 17));
    const Lanes rounded = _mm256_srli_epi64(_mm256_add_epi64(lo, _mm256_set1_epi64x(int64_t{1} << 15)), 16);
    const Lanes mag = _mm256_add_epi64(_mm256_slli_epi64(hi, 16), rounded);
    return WithSign(mag, _mm256_xor_si256(s.neg, f.neg));
}

// Wide * Wide (rounded by 2^32): with |x| = xh 2^32 + xl and |y| = yh 2^32 + yl,
// round(|x||y| / 2^32) = xh yh 2^32 + xh yl + xl yh + round(xl yl / 2^32).
LOCKBOX_AVX2 inline Lanes MulWW(Lanes& unsafe, const Split& sx, const Split& sy) {
    const Lanes xh = _mm256_srli_epi64(sx.mag, 32), yh = _mm256_srli_epi64(sy.mag, 32);
    const Lanes hh = _mm256_mul_epu32(xh, yh);
    const Lanes hl = _mm256_mul_epu32(xh, sy.mag);
    const Lanes lh = _mm256_mul_epu32(sx.mag, yh);
    const Lanes ll = _mm256_mul_epu32(sx.mag, sy.mag);
    // hh < 2^26, hl and lh < 2^57: the magnitude stays below 2^59.
    Flag(unsafe, _mm256_srli_epi64(hh, kBoundBits - 33));
    Flag(unsafe, _mm256_or_si256(_mm256_srli_epi64(hl, kBoundBits - 2), _mm256_srli_epi64(lh, kBoundBits - 2)));
    // floor((ll + 2^31) / 2^32) == floor((floor(ll / 2) + 2^30) / 2^31), without a carry out.
    const Lanes rounded =
        _mm256_srli_epi64(_mm256_add_epi64(_mm256_srli_epi64(ll, 1), _mm256_set1_epi64x(int64_t{1} << 30)), 31);
    const Lanes mag = _mm256_add_epi64(_mm256_add_epi64(_mm256_slli_epi64(hh, 32), _mm256_add_epi64(hl, lh)), rounded);
    return WithSign(mag, _mm256_xor_si256(sx.neg, sy.neg));
}
LOCKBOX_AVX2 inline Lanes MulWW(Lanes& unsafe, Lanes x, const Split& y) { return MulWW(unsafe, SplitSign(x), y); }

LOCKBOX_AVX2 inline void Spill(Lanes v, int64_t out[4]) { _mm256_storeu_si256(reinterpret_cast<Lanes*>(out), v); }

// The velocities of the two bodies of four rows (lane k from row k).
struct Pair {
    Lanes vAx, vAy, wA, vBx, vBy, wB;
};

// The bodies a[k] and b[k] of four rows, each value flagged where beyond the bound.
LOCKBOX_AVX2 inline Pair LoadPair(Lanes& unsafe, const b2Velocity* velocities, const int32_t (&a)[4],
                                  const int32_t (&b)[4]) {
    alignas(32) int64_t raw[6][4];
    for (int k = 0; k < 4; ++k) {
        const b2Velocity& va = velocities[a[k]];
        const b2Velocity& vb = velocities[b[k]];
        raw[0][k] = va.v.x.Raw();
        raw[1][k] = va.v.y.Raw();
        raw[2][k] = va.w.Raw();
        raw[3][k] = vb.v.x.Raw();
        raw[4][k] = vb.v.y.Raw();
        raw[5][k] = vb.w.Raw();
    }
    Pair p;
    Lanes* const fields[6] = {&p.vAx, &p.vAy, &p.wA, &p.vBx, &p.vBy, &p.wB};
    for (int f = 0; f < 6; ++f) {
        *fields[f] = _mm256_load_si256(reinterpret_cast<const Lanes*>(raw[f]));
        Bound(unsafe, *fields[f]);
    }
    return p;
}

// A pair's values back in memory, component by component (raw[c][k]: component c of lane k in
// LoadPair's order), for the writes of the lanes that were followed.
LOCKBOX_AVX2 inline void SpillPair(const Pair& p, int64_t (&raw)[6][4]) {
    Spill(p.vAx, raw[0]);
    Spill(p.vAy, raw[1]);
    Spill(p.wA, raw[2]);
    Spill(p.vBx, raw[3]);
    Spill(p.vBy, raw[4]);
    Spill(p.wB, raw[5]);
}

}  // namespace lockbox::lanes
#endif  // LOCKBOX_INTEGER_LANES
