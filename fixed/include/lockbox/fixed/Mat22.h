#pragma once
/// @file
/// b2Mat22 (the manual's Math module): a 2x2 matrix stored in column-major order.
///
/// The determinant is formed exactly (Q32.32 in 64 bits) and each result is one rounded
/// division of exact integers, so the inverse and the solve stay accurate wherever the
/// result itself fits Q16.16.

#include "lockbox/fixed/Vec2.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox {

namespace detail {
/// round(num * 2^shift / den) for exact integers, saturated to a Q16.16 raw; den == 0 gives 0
/// (the manual's convention for singular matrices).
constexpr Fixed DivExactToFixed(const S128& num, const S128& den, int shift, const char* op) noexcept {
    if (IsZero(den)) return Fixed();
    S128 n = num;
    n.mag = ShlU128(n.mag, shift);
    const S128 q = DivRoundS128(n, den);
    if (q.mag.hi != 0 || q.mag.lo > static_cast<uint64_t>(Fixed::kMaxRaw)) [[unlikely]] {
        OnOverflow(op, 0, 0);
        return Fixed::FromRaw(q.negative ? -Fixed::kMaxRaw : Fixed::kMaxRaw);
    }
    const int32_t m = static_cast<int32_t>(q.mag.lo);
    return Fixed::FromRaw(q.negative ? -m : m);
}
}  // namespace detail

/// A 2x2 matrix of Q16.16 entries stored by columns (ex, ey), as in Box2D: rotations, small
/// effective-mass matrices and their inverses.
struct b2Mat22 {
    b2Vec2 ex;  ///< first column
    b2Vec2 ey;  ///< second column

    constexpr b2Mat22() noexcept = default;
    /// The matrix with columns c1 and c2.
    constexpr b2Mat22(const b2Vec2& c1, const b2Vec2& c2) noexcept : ex(c1), ey(c2) {}
    /// The matrix [a11 a12; a21 a22], given row by row (stored by columns).
    constexpr b2Mat22(Fixed a11, Fixed a12, Fixed a21, Fixed a22) noexcept : ex(a11, a21), ey(a12, a22) {}

    /// Sets the columns to c1 and c2.
    constexpr void Set(const b2Vec2& c1, const b2Vec2& c2) noexcept {
        ex = c1;
        ey = c2;
    }
    /// Sets the identity matrix.
    constexpr void SetIdentity() noexcept {
        ex.Set(1, 0);
        ey.Set(0, 1);
    }
    /// Sets every entry to zero.
    constexpr void SetZero() noexcept {
        ex.SetZero();
        ey.SetZero();
    }

    /// Exact determinant as Q32.32.
    constexpr Wide DeterminantWide() const noexcept {
        return Wide::FromRaw(detail::DiffOfProducts(ex.x.Raw(), ey.y.Raw(), ey.x.Raw(), ex.y.Raw()));
    }

    /// The inverse; a singular matrix gives the zero matrix (as Box2D's det = 0 path).
    constexpr b2Mat22 GetInverse() const noexcept {
        const detail::S128 det = detail::MulS64(DeterminantWide().Raw(), 1);
        auto entry = [&](Fixed v) {
            return detail::DivExactToFixed(detail::MulS64(v.Raw(), 1), det, 32, "b2Mat22::GetInverse");
        };
        b2Mat22 b;
        b.ex.x = entry(ey.y);
        b.ey.x = entry(-ey.x);
        b.ex.y = entry(-ex.y);
        b.ey.y = entry(ex.x);
        return b;
    }

    /// Solves A * x = b. A singular matrix gives x = 0.
    constexpr b2Vec2 Solve(const b2Vec2& b) const noexcept {
        const detail::S128 det = detail::MulS64(DeterminantWide().Raw(), 1);
        const detail::S128 nx =
            detail::SubS128(detail::MulS64(ey.y.Raw(), b.x.Raw()), detail::MulS64(ey.x.Raw(), b.y.Raw()));
        const detail::S128 ny =
            detail::SubS128(detail::MulS64(ex.x.Raw(), b.y.Raw()), detail::MulS64(ex.y.Raw(), b.x.Raw()));
        return {detail::DivExactToFixed(nx, det, 16, "b2Mat22::Solve"),
                detail::DivExactToFixed(ny, det, 16, "b2Mat22::Solve")};
    }
};

/// Entry-wise sum, each entry with Fixed's saturation.
constexpr b2Mat22 operator+(const b2Mat22& A, const b2Mat22& B) noexcept { return {A.ex + B.ex, A.ey + B.ey}; }

/// A * v, each component an exact sum rounded once.
constexpr b2Vec2 b2Mul(const b2Mat22& A, const b2Vec2& v) noexcept {
    return {Wide::FromRaw(detail::SumOfProducts(A.ex.x.Raw(), v.x.Raw(), A.ey.x.Raw(), v.y.Raw())).ToFixed(),
            Wide::FromRaw(detail::SumOfProducts(A.ex.y.Raw(), v.x.Raw(), A.ey.y.Raw(), v.y.Raw())).ToFixed()};
}
/// transpose(A) * v.
constexpr b2Vec2 b2MulT(const b2Mat22& A, const b2Vec2& v) noexcept { return {b2Dot(v, A.ex), b2Dot(v, A.ey)}; }
/// A * B.
constexpr b2Mat22 b2Mul(const b2Mat22& A, const b2Mat22& B) noexcept { return {b2Mul(A, B.ex), b2Mul(A, B.ey)}; }
/// transpose(A) * B.
constexpr b2Mat22 b2MulT(const b2Mat22& A, const b2Mat22& B) noexcept {
    return {b2Vec2(b2Dot(A.ex, B.ex), b2Dot(A.ey, B.ex)), b2Vec2(b2Dot(A.ex, B.ey), b2Dot(A.ey, B.ey))};
}
/// Entry-wise absolute value.
constexpr b2Mat22 b2Abs(const b2Mat22& A) noexcept { return {b2Abs(A.ex), b2Abs(A.ey)}; }

}  // namespace lockbox
