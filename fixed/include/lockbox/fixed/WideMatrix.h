#pragma once
/// @file
/// Q32.32 vectors and matrices for the joint solvers: impulses (N*s), effective-mass matrices
/// K (1/kg) and their solves.
///
/// Why: K's entries are inverse masses (up to ~1e3 1/kg) plus inverse inertias times squared
/// arms (up to ~1e6 and more), which overflow Q16.16, and its 3x3 determinant spans 1e-9..5e11
/// (docs/numerics.md, "Formats"). Here K is stored in Wide, normalised by a power of two so that
/// its largest entry has kNormBits (a 2x2 K: kNormBits22) significant bits, and solved by
/// Cramer's rule with exact 128-bit cofactors and one rounded division per component.

#include <bit>
#include <cstdint>
#include <type_traits>

#include "lockbox/fixed/Math.h"
#include "lockbox/fixed/WideVec.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox {

namespace detail {
#ifdef LOCKBOX_NATIVE_INT128
// Native twins of the sign-magnitude S128 paths below, for the joint solvers' hot loops. Each
// computes the same exact integer and rounds it the same way (half away from zero on the
// magnitude, saturating to +-INT64_MAX with the same overflow report), so the bits match the
// portable limbs (tested on random and extreme inputs in wide_matrix_test, and by the
// portable128 preset's golden hashes).

/// |v| of a value known to be above -2^127.
inline NativeU128 MagnitudeU128(NativeI128 v) noexcept {
    return v < 0 ? static_cast<NativeU128>(0) - static_cast<NativeU128>(v) : static_cast<NativeU128>(v);
}

/// The sign-and-magnitude form of a native value.
inline S128 FromNative(NativeI128 v) noexcept {
    const NativeU128 m = MagnitudeU128(v);
    return S128{v < 0, U128{static_cast<uint64_t>(m >> 64), static_cast<uint64_t>(m)}};
}

#endif

/// r x P of raw Q16.16 r and raw Q32.32 P, rounded once to a Q32.32 raw (the portable form).
constexpr int64_t CrossArmImpulseRaw(int32_t rx, int32_t ry, int64_t px, int64_t py, const char* op) noexcept {
    const S128 e = SubS128(MulS64(rx, py), MulS64(ry, px));
    return NarrowWide(ShrRoundS128(e, 16), op, rx, py);
}
}  // namespace detail

/// Exact r x P (N*m*s) of a Q16.16 arm and a Q32.32 impulse, rounded once to Q32.32.
constexpr Wide b2Cross(const b2Vec2& r, const b2WideVec2& p) noexcept {
    constexpr const char* kOp = "b2Cross(b2Vec2, b2WideVec2)";
#ifdef LOCKBOX_NATIVE_INT128
    if (!std::is_constant_evaluated()) {
        using namespace detail;
        // |r| < 2^31 and |P| < 2^63: each product is below 2^94, the difference below 2^95.
        const NativeI128 e =
            static_cast<NativeI128>(r.x.Raw()) * p.y.Raw() - static_cast<NativeI128>(r.y.Raw()) * p.x.Raw();
        const NativeU128 mag = (MagnitudeU128(e) + (NativeU128{1} << 15)) >> 16;
        return Wide::FromRaw(NarrowMagnitude(mag, e < 0, kOp, r.x.Raw(), p.y.Raw()));
    }
#endif
    return Wide::FromRaw(detail::CrossArmImpulseRaw(r.x.Raw(), r.y.Raw(), p.x.Raw(), p.y.Raw(), kOp));
}

namespace detail {
/// round(n * 2^shift / d) as a saturated Q32.32 raw, shift >= 0. When n << shift would not fit
/// 127 bits, d is shifted right instead (d is then so large that its dropped bits do not
/// matter). A zero (or vanishing) d is the singular case and gives 0, as Box2D's solves do.
constexpr int64_t DivShiftS128(S128 n, S128 d, int shift, const char* op) noexcept {
    if (IsZero(n)) return 0;
    if (shift < 0) {
        // Only a 2x2 K whose largest entry has 64 bits (s = 33) gets here: divide n by 2^-shift
        // first (rounded), which keeps every shift below non-negative.
        n = ShrRoundS128(n, -shift);
        shift = 0;
        if (IsZero(n)) return 0;
    }
    int room = 126 - BitWidthU128(n.mag);
    if (room < 0) {
        // A numerator of 127 or 128 bits (extreme cofactors, e.g. from a restored image with
        // huge masses): drop its lowest bits (a relative error below 2^-125) and carry them
        // into the shift, so no shift below is negative.
        n.mag = ShrU128(n.mag, -room);
        shift -= room;
        room = 0;
    }
    if (shift <= room) {
        n.mag = ShlU128(n.mag, shift);
    } else {
        n.mag = ShlU128(n.mag, room);
        d = ShrRoundS128(d, shift - room);
    }
    if (IsZero(d)) return 0;
    return NarrowWide(DivRoundS128(n, d), op, 0, 0);
}

#ifdef LOCKBOX_NATIVE_INT128
/// DivShiftS128 of native values. The common case (n << shift fits in 126 bits, so d is not
/// shifted) is one native division; the rest goes through the portable code.
inline int64_t DivShiftNative(NativeI128 n, NativeI128 d, int shift, const char* op) noexcept {
    if (n == 0) return 0;
    NativeU128 nm = MagnitudeU128(n);
    const auto hi = static_cast<uint64_t>(nm >> 64);
    const int width = hi != 0 ? 64 + static_cast<int>(std::bit_width(hi))
                              : static_cast<int>(std::bit_width(static_cast<uint64_t>(nm)));
    if (shift < 0 || shift > 126 - width) {
        return DivShiftS128(FromNative(n), FromNative(d), shift, op);
    }
    const NativeU128 dm = MagnitudeU128(d);
    if (dm == 0) return 0;
    nm <<= shift;
    const NativeDivMod qr = DivModNative(nm, dm);
    NativeU128 q = qr.quot;
    const NativeU128 rem = qr.rem;
    if (rem >= dm - rem) ++q;  // 2 rem >= d: ties away from zero
    return NarrowMagnitude(q, q != 0 && ((n < 0) != (d < 0)), op, 0, 0);
}

/// DivShiftNative for a divisor of at most 2^63 (a normalised 2x2 determinant). When n << shift
/// fits in 126 bits and the quotient in 64, that is one 128-by-64-bit division; anything else
/// (a saturating quotient, a zero divisor, a negative or large shift) goes the general way. The
/// bits are DivShiftNative's: the same exact quotient, rounded the same way.
[[gnu::always_inline]] inline int64_t DivShiftNative64(NativeI128 n, uint64_t dMag, bool dNegative, int shift,
                                                       const char* op) noexcept {
    // A 2x2 solve's shift is 32 - s with s >= -30 (NormShift of a non-zero K), so at most 62; the
    // word arithmetic below needs 62 - shift >= 0, and 63 takes the general way.
    if (shift >= 0 && shift <= 62) {
        const NativeU128 nm = MagnitudeU128(n);
        const auto hi = static_cast<uint64_t>(nm >> 64), lo = static_cast<uint64_t>(nm);
        // nm << shift below 2^126 exactly when nm's high word is below 2^(62 - shift).
        if ((hi >> (62 - shift)) == 0) {
            // The shifted words (lo's top bits go right in two steps, so that shift 0 is defined).
            const uint64_t shiftedHi = (hi << shift) | ((lo >> 1) >> (63 - shift));
            if (shiftedHi < dMag) {
                uint64_t rem = 0;
                const uint64_t quot = DivWordNative(shiftedHi, lo << shift, dMag, &rem);
                // 2 rem >= d: ties away from zero (the quotient plus one may reach 2^64).
                const NativeU128 q = NativeU128{quot} + (rem >= dMag - rem ? 1u : 0u);
                return NarrowMagnitude(q, q != 0 && ((n < 0) != dNegative), op, 0, 0);
            }
        }
    }
    const auto d = static_cast<NativeI128>(dMag);
    return DivShiftNative(n, dNegative ? -d : d, shift, op);
}
#endif

/// Significant bits kept in the largest entry of a normalised 3x3 K. 36 bits (a relative
/// resolution of 1.5e-11, far better than float's 6e-8) leave room for the exact 3x3
/// cofactor sums times a right-hand side of up to 2^47 raw (32768 m/s) inside 127 bits.
inline constexpr int kNormBits = 36;

/// Significant bits kept in the largest entry of a normalised 2x2 K. 31 bits (a relative
/// resolution of 4.7e-10, still 100 times finer than float's) keep the determinant within 2^63,
/// so each solve is one 128-by-64-bit division instead of a general 128-bit one.
inline constexpr int kNormBits22 = 31;

/// The power-of-two exponent s that brings the largest |raw| to `bits` significant bits.
constexpr int NormShift(const int64_t* raws, int count, int bits = kNormBits) noexcept {
    uint64_t m = 0;
    for (int i = 0; i < count; ++i) m |= AbsU64(raws[i]);
    if (m == 0) return 0;
    return BitWidthU128(U128{0, m}) - bits;
}

/// raw * 2^-s with rounding (s > 0) or exact raw * 2^-s (s <= 0, never overflows since the
/// result has at most kNormBits bits).
constexpr int64_t ScaleRaw(int64_t raw, int s) noexcept {
    if (s > 0) {
        // s <= 33 (64 - kNormBits22): |raw| + half stays below 2^64, so 64 bits round exactly.
        const uint64_t m = (AbsU64(raw) + (uint64_t{1} << (s - 1))) >> s;
        return raw < 0 ? -static_cast<int64_t>(m) : static_cast<int64_t>(m);
    }
    return raw * (int64_t{1} << (-s));
}
}  // namespace detail

namespace detail {
/// floor(sqrt(n)) of a 128-bit value (digit by digit; off the hot path: impulse clamps only).
constexpr uint64_t IsqrtU128(U128 n) noexcept {
    U128 rem{0, 0};
    U128 root{0, 0};
    for (int i = 63; i >= 0; --i) {
        // Bring down the next two bits of n.
        rem = AddU128(ShlU128(rem, 2), ShrU128(n, 2 * i).lo & 3u);
        root = ShlU128(root, 1);
        const U128 trial = AddU128(ShlU128(root, 1), 1);
        if (!LessU128(rem, trial)) {
            rem = SubU128(rem, trial);
            root = AddU128(root, 1);
        }
    }
    return root.lo;
}
}  // namespace detail

/// Scales v down to length maxLength (>= 0) when it is longer; otherwise returns v. The test
/// compares exact 128-bit squares (the Q32.32 square of a 1e5 N*s impulse would overflow) and
/// the scaling is one rounded division per component. Used for the friction and mouse clamps.
constexpr b2WideVec2 b2ClampLength(const b2WideVec2& v, Wide maxLength) noexcept {
    using namespace detail;
    const U128 sum =
        AddU128(MulU64(AbsU64(v.x.Raw()), AbsU64(v.x.Raw())), MulU64(AbsU64(v.y.Raw()), AbsU64(v.y.Raw())));
    const int64_t maxRaw = maxLength.Raw() > 0 ? maxLength.Raw() : 0;
    const U128 lim = MulU64(static_cast<uint64_t>(maxRaw), static_cast<uint64_t>(maxRaw));
    if (!LessU128(lim, sum)) return v;
    const uint64_t len = IsqrtU128(sum);  // > maxRaw >= 0, so non-zero
    const S128 d{false, U128{0, len}};
    auto scale = [&](Wide c) {
        return Wide::FromRaw(NarrowWide(DivRoundS128(MulS64(c.Raw(), maxRaw), d), "b2ClampLength", c.Raw(), maxRaw));
    };
    return {scale(v.x), scale(v.y)};
}

/// A 2x2 K made ready for many solves. Its normalisation and determinant depend on K only, and
/// K stays fixed through a step's velocity iterations, so a joint prepares it once per step
/// (InitVelocityConstraints) and each iteration pays only for the right-hand side. Solve gives
/// the bits of b2WideMat22::Solve, which is this same code run once.
struct b2WideSolver22 {
    int s = 0;  ///< the normalising exponent (NormShift)
    /// K's entries scaled by 2^-s (raw Q32.32 values shifted right by the normalising exponent).
    ///@{
    int64_t a11 = 0, a21 = 0, a12 = 0, a22 = 0;
    ///@}
    detail::S128 det;  ///< exact a11 a22 - a12 a21

    constexpr b2WideSolver22() noexcept = default;
    /// Prepares K = [ex ey] (Q32.32 columns).
    constexpr b2WideSolver22(const b2WideVec2& ex, const b2WideVec2& ey) noexcept {
        using namespace detail;
        const int64_t raws[4] = {ex.x.Raw(), ex.y.Raw(), ey.x.Raw(), ey.y.Raw()};
        s = NormShift(raws, 4, kNormBits22);
        a11 = ScaleRaw(ex.x.Raw(), s);
        a21 = ScaleRaw(ex.y.Raw(), s);
        a12 = ScaleRaw(ey.x.Raw(), s);
        a22 = ScaleRaw(ey.y.Raw(), s);
#ifdef LOCKBOX_NATIVE_INT128
        if (!std::is_constant_evaluated()) {
            // |a| <= 2^31: the exact determinant is at most 2^63 either way.
            det = FromNative(static_cast<NativeI128>(a11) * a22 - static_cast<NativeI128>(a12) * a21);
            return;
        }
#endif
        det = SubS128(MulS64(a11, a22), MulS64(a12, a21));
    }

    /// Solves K x = b for a Q32.32 right-hand side (m/s); x is an impulse (N*s). A singular K
    /// gives x = 0.
    constexpr b2WideVec2 Solve(const b2WideVec2& b) const noexcept { return {SolveX(b), SolveY(b)}; }
    /// Solve through the portable 128-bit limbs only (the same bits; for the tests).
    constexpr b2WideVec2 SolvePortable(const b2WideVec2& b) const noexcept {
        return {Wide::FromRaw(QuotientPortable(a22, b.x.Raw(), a12, b.y.Raw())),
                Wide::FromRaw(QuotientPortable(a11, b.y.Raw(), a21, b.x.Raw()))};
    }
    /// Solves K x = b for a Q16.16 right-hand side.
    constexpr b2WideVec2 Solve(const b2Vec2& b) const noexcept { return Solve(b2WideVec2(b)); }
    /// Solve(b).x alone (the same bits and the same overflow report, one division).
    constexpr Wide SolveX(const b2WideVec2& b) const noexcept {
        return Wide::FromRaw(Quotient(a22, b.x.Raw(), a12, b.y.Raw()));
    }
    /// Solve(b).y alone (the same bits and the same overflow report, one division).
    constexpr Wide SolveY(const b2WideVec2& b) const noexcept {
        return Wide::FromRaw(Quotient(a11, b.y.Raw(), a21, b.x.Raw()));
    }

private:
    /// One component of the solution by Cramer's rule: (p bp - q bq) / det as a Q32.32 raw.
    [[gnu::always_inline]] constexpr int64_t Quotient(int64_t p, int64_t bp, int64_t q, int64_t bq) const noexcept {
#ifdef LOCKBOX_NATIVE_INT128
        if (!std::is_constant_evaluated()) {
            using detail::NativeI128;
            // |a| <= 2^31 (normalised) and |b| <= 2^63: products below 2^95, exact. |det| <= 2^63,
            // so its magnitude is its low limb.
            const NativeI128 n = static_cast<NativeI128>(p) * bp - static_cast<NativeI128>(q) * bq;
            return detail::DivShiftNative64(n, det.mag.lo, det.negative, 32 - s, "b2WideMat22::Solve");
        }
#endif
        return QuotientPortable(p, bp, q, bq);
    }
    /// Quotient through the portable limbs.
    constexpr int64_t QuotientPortable(int64_t p, int64_t bp, int64_t q, int64_t bq) const noexcept {
        using namespace detail;
        // Raw bookkeeping: x_raw = (n / det) * 2^(32 - s), see WideMatrix.h's header.
        return DivShiftS128(SubS128(MulS64(p, bp), MulS64(q, bq)), det, 32 - s, "b2WideMat22::Solve");
    }
};

/// A 3x3 K made ready for many solves (see b2WideSolver22): Solve33 gives the bits of
/// b2WideMat33::Solve33.
struct b2WideSolver33 {
    int s = 0;          ///< the normalising exponent (NormShift)
    int64_t m[9] = {};  ///< K's columns scaled by 2^-s: c0 = m[0..2], c1 = m[3..5], c2 = m[6..8]
    detail::S128 det;   ///< exact c0 . (c1 x c2)

    constexpr b2WideSolver33() noexcept = default;
    /// Prepares K = [ex ey ez] (Q32.32 columns).
    constexpr b2WideSolver33(const b2WideVec3& ex, const b2WideVec3& ey, const b2WideVec3& ez) noexcept {
        using namespace detail;
        const int64_t raws[9] = {ex.x.Raw(), ex.y.Raw(), ex.z.Raw(), ey.x.Raw(), ey.y.Raw(),
                                 ey.z.Raw(), ez.x.Raw(), ez.y.Raw(), ez.z.Raw()};
        s = NormShift(raws, 9);
        for (int i = 0; i < 9; ++i) m[i] = ScaleRaw(raws[i], s);
#ifdef LOCKBOX_NATIVE_INT128
        if (!std::is_constant_evaluated()) {
            det = FromNative(NativeTriple(m, m + 3, m + 6));  // entries <= 2^36: below 2^111
            return;
        }
#endif
        det = Triple(m, m + 3, m + 6);
    }

    /// Solves K x = b (b in m/s and rad/s as Q32.32). A singular K gives x = 0.
    constexpr b2WideVec3 Solve33(const b2WideVec3& b) const noexcept {
#ifdef LOCKBOX_NATIVE_INT128
        // A right-hand side of Q16.16 range (|raw| <= 2^47, every joint's velocity error) keeps
        // every cofactor sum below 2^122: native products are then exact, as the limbs are.
        constexpr int64_t kLimit = int64_t{1} << 47;
        auto small = [](Wide v) { return v.Raw() >= -kLimit && v.Raw() <= kLimit; };
        if (!std::is_constant_evaluated() && small(b.x) && small(b.y) && small(b.z)) {
            using namespace detail;
            const int64_t bv[3] = {b.x.Raw(), b.y.Raw(), b.z.Raw()};
            const NativeI128 d = NativeDet();
            return {Wide::FromRaw(DivShiftNative(NativeTriple(bv, m + 3, m + 6), d, 32 - s, "b2WideMat33::Solve33")),
                    Wide::FromRaw(DivShiftNative(NativeTriple(m, bv, m + 6), d, 32 - s, "b2WideMat33::Solve33")),
                    Wide::FromRaw(DivShiftNative(NativeTriple(m, m + 3, bv), d, 32 - s, "b2WideMat33::Solve33"))};
        }
#endif
        return Solve33Portable(b);
    }
    /// Solve33 through the portable 128-bit limbs only (the same bits; for the tests).
    constexpr b2WideVec3 Solve33Portable(const b2WideVec3& b) const noexcept {
        using namespace detail;
        const int64_t bv[3] = {b.x.Raw(), b.y.Raw(), b.z.Raw()};
        const S128 nx = Triple(bv, m + 3, m + 6);
        const S128 ny = Triple(m, bv, m + 6);
        const S128 nz = Triple(m, m + 3, bv);
        return {Wide::FromRaw(DivShiftS128(nx, det, 32 - s, "b2WideMat33::Solve33")),
                Wide::FromRaw(DivShiftS128(ny, det, 32 - s, "b2WideMat33::Solve33")),
                Wide::FromRaw(DivShiftS128(nz, det, 32 - s, "b2WideMat33::Solve33"))};
    }
    /// Solves K x = b for a Q16.16 right-hand side.
    constexpr b2WideVec3 Solve33(const b2Vec3& b) const noexcept { return Solve33(b2WideVec3(b)); }

private:
#ifdef LOCKBOX_NATIVE_INT128
    /// det as a native value (|det| < 2^110).
    detail::NativeI128 NativeDet() const noexcept {
        const auto v =
            static_cast<detail::NativeI128>((static_cast<detail::NativeU128>(det.mag.hi) << 64) | det.mag.lo);
        return det.negative ? -v : v;
    }
    /// Triple in native integers; callers keep every entry below 2^47 (see Solve33).
    static detail::NativeI128 NativeTriple(const int64_t* a, const int64_t* p, const int64_t* q) noexcept {
        using detail::NativeI128;
        const NativeI128 cx = static_cast<NativeI128>(p[1]) * q[2] - static_cast<NativeI128>(p[2]) * q[1];
        const NativeI128 cy = static_cast<NativeI128>(p[2]) * q[0] - static_cast<NativeI128>(p[0]) * q[2];
        const NativeI128 cz = static_cast<NativeI128>(p[0]) * q[1] - static_cast<NativeI128>(p[1]) * q[0];
        return cx * a[0] + cy * a[1] + cz * a[2];
    }
#endif
    /// Exact a . (p x q) of raw 3-vectors.
    static constexpr detail::S128 Triple(const int64_t* a, const int64_t* p, const int64_t* q) noexcept {
        using namespace detail;
        const S128 cx = SubS128(MulS64(p[1], q[2]), MulS64(p[2], q[1]));
        const S128 cy = SubS128(MulS64(p[2], q[0]), MulS64(p[0], q[2]));
        const S128 cz = SubS128(MulS64(p[0], q[1]), MulS64(p[1], q[0]));
        return AddS128(AddS128(MulS128S64(cx, a[0]), MulS128S64(cy, a[1])), MulS128S64(cz, a[2]));
    }
};

/// Symmetric or general 2x2 matrix of Q32.32 entries, column-major (an effective-mass K, 1/kg).
struct b2WideMat22 {
    /// The two columns (Q32.32 entries, 1/kg for an effective mass).
    ///@{
    b2WideVec2 ex;
    b2WideVec2 ey;
    ///@}

    /// Solves K x = b for a Q32.32 right-hand side (m/s); x is an impulse (N*s). A singular K
    /// gives x = 0. For many solves with one K, prepare a b2WideSolver22 once.
    constexpr b2WideVec2 Solve(const b2WideVec2& b) const noexcept { return Prepared().Solve(b); }
    /// Solves K x = b for a Q16.16 right-hand side.
    constexpr b2WideVec2 Solve(const b2Vec2& b) const noexcept { return Solve(b2WideVec2(b)); }

    /// The matrix prepared for many solves.
    constexpr b2WideSolver22 Prepared() const noexcept { return b2WideSolver22(ex, ey); }
};

namespace math {
/// K^-1 of a prepared K, column by column, each entry exactly rounded (a singular K gives the
/// zero matrix). For a K applied many times per step: a product per iteration instead of a
/// solve with its two 128-bit divisions.
constexpr b2WideMat22 Inverse(const b2WideSolver22& k) noexcept {
    const b2WideVec2 ex = k.Solve(b2WideVec2(Wide(1), Wide()));
    // The inverse of a symmetric K is symmetric: its (1, 2) entry has the same numerator and
    // determinant as its (2, 1) entry, so one division serves both. A saturated entry is
    // divided again, so that its overflow is reported as often as by two solves.
    if (k.a12 == k.a21 && ex.y.Raw() != Wide::kMaxRaw && ex.y.Raw() != -Wide::kMaxRaw) {
        return {ex, b2WideVec2(ex.y, k.SolveY(b2WideVec2(Wide(), Wide(1))))};
    }
    return {ex, k.Solve(b2WideVec2(Wide(), Wide(1)))};
}

/// M v for a Q16.16 (b2Vec2) or Q32.32 (b2WideVec2) vector, each component two rounded
/// products summed (checked).
template <class Vec>
constexpr b2WideVec2 Mul(const b2WideMat22& m, const Vec& v) noexcept {
    return {m.ex.x * v.x + m.ey.x * v.y, m.ex.y * v.x + m.ey.y * v.y};
}
}  // namespace math

/// 3x3 matrix of Q32.32 entries, column-major (the point-plus-angle K of revolute, prismatic
/// and weld joints).
struct b2WideMat33 {
    /// The three columns (Q32.32 entries).
    ///@{
    b2WideVec3 ex;
    b2WideVec3 ey;
    b2WideVec3 ez;
    ///@}

    /// Solves K x = b (b in m/s and rad/s as Q32.32). A singular K gives x = 0. For many solves
    /// with one K, prepare a b2WideSolver33 once.
    constexpr b2WideVec3 Solve33(const b2WideVec3& b) const noexcept { return Prepared().Solve33(b); }
    /// Solves K x = b for a Q16.16 right-hand side.
    constexpr b2WideVec3 Solve33(const b2Vec3& b) const noexcept { return Solve33(b2WideVec3(b)); }

    /// Solves the upper 2x2 block: K22 x = b. A singular block gives x = 0.
    constexpr b2WideVec2 Solve22(const b2WideVec2& b) const noexcept { return Upper22().Solve(b); }
    /// Solves the upper 2x2 block K22 x = b for a Q16.16 right-hand side; a singular block
    /// gives x = 0.
    constexpr b2WideVec2 Solve22(const b2Vec2& b) const noexcept { return Solve22(b2WideVec2(b)); }

    /// The upper 2x2 block prepared for many solves.
    constexpr b2WideSolver22 Upper22() const noexcept { return b2WideSolver22({ex.x, ex.y}, {ey.x, ey.y}); }
    /// The whole matrix prepared for many solves.
    constexpr b2WideSolver33 Prepared() const noexcept { return b2WideSolver33(ex, ey, ez); }
};

}  // namespace lockbox
