#pragma once
/// @file
/// b2Mat33 (the manual's Math module): a 3x3 matrix in column-major order, for the joints'
/// point-plus-angle constraints.
///
/// Determinants and cofactors are formed exactly in 128 bits (a triple product of raw
/// Q16.16 values is below 2^95) and each result is one rounded division, so a solve is as
/// accurate as the Q16.16 result allows, whatever the conditioning of the inputs.

#include "lockbox/fixed/Mat22.h"
#include "lockbox/fixed/Vec3.h"

namespace lockbox {

/// A 3x3 matrix of Q16.16 entries stored by columns (ex, ey, ez), as in Box2D: the point-plus-angle
/// effective mass of the weld, revolute and prismatic joints.
struct b2Mat33 {
    /// The three columns.
    ///@{
    b2Vec3 ex;
    b2Vec3 ey;
    b2Vec3 ez;
    ///@}

    constexpr b2Mat33() noexcept = default;
    /// The matrix with columns c1, c2 and c3.
    constexpr b2Mat33(const b2Vec3& c1, const b2Vec3& c2, const b2Vec3& c3) noexcept : ex(c1), ey(c2), ez(c3) {}

    /// Sets every entry to zero.
    constexpr void SetZero() noexcept {
        ex.SetZero();
        ey.SetZero();
        ez.SetZero();
    }

    /// Solves A * x = b. A singular matrix gives x = 0.
    constexpr b2Vec3 Solve33(const b2Vec3& b) const noexcept {
        const detail::S128 det = Triple(ex, ey, ez);
        return {detail::DivExactToFixed(Triple(b, ey, ez), det, 16, "b2Mat33::Solve33"),
                detail::DivExactToFixed(Triple(ex, b, ez), det, 16, "b2Mat33::Solve33"),
                detail::DivExactToFixed(Triple(ex, ey, b), det, 16, "b2Mat33::Solve33")};
    }

    /// Solves the upper 2x2 block: A22 * x = b. A singular block gives x = 0.
    constexpr b2Vec2 Solve22(const b2Vec2& b) const noexcept { return b2Mat22(ex.x, ey.x, ex.y, ey.y).Solve(b); }

    /// Inverse of the upper 2x2 block into M, with the third row and column zero.
    constexpr void GetInverse22(b2Mat33* M) const noexcept {
        const b2Mat22 inv = b2Mat22(ex.x, ey.x, ex.y, ey.y).GetInverse();
        M->ex = b2Vec3(inv.ex.x, inv.ex.y, 0);
        M->ey = b2Vec3(inv.ey.x, inv.ey.y, 0);
        M->ez = b2Vec3(0, 0, 0);
    }

    /// Inverse of a symmetric matrix into M (only the upper triangle of this is read).
    /// A singular matrix gives the zero matrix.
    constexpr void GetSymInverse33(b2Mat33* M) const noexcept {
        const detail::S128 det = Triple(ex, ey, ez);
        const Fixed a11 = ex.x, a12 = ey.x, a13 = ez.x, a22 = ey.y, a23 = ez.y, a33 = ez.z;
        auto cof = [&](Fixed p, Fixed q, Fixed r, Fixed s) {
            const detail::S128 c = detail::SubS128(detail::MulS64(p.Raw(), q.Raw()), detail::MulS64(r.Raw(), s.Raw()));
            return detail::DivExactToFixed(c, det, 32, "b2Mat33::GetSymInverse33");
        };
        M->ex.x = cof(a22, a33, a23, a23);
        M->ex.y = cof(a13, a23, a12, a33);
        M->ex.z = cof(a12, a23, a13, a22);
        M->ey.x = M->ex.y;
        M->ey.y = cof(a11, a33, a13, a13);
        M->ey.z = cof(a13, a12, a11, a23);
        M->ez.x = M->ex.z;
        M->ez.y = M->ey.z;
        M->ez.z = cof(a11, a22, a12, a12);
    }

private:
    /// Exact a . (b x c) of raw values (a Q48.48 value in 128 bits).
    static constexpr detail::S128 Triple(const b2Vec3& a, const b2Vec3& b, const b2Vec3& c) noexcept {
        using namespace detail;
        auto crossTerm = [](Fixed p, Fixed q, Fixed r, Fixed s) {
            return SubS128(MulS64(p.Raw(), q.Raw()), MulS64(r.Raw(), s.Raw()));
        };
        const S128 cx = crossTerm(b.y, c.z, b.z, c.y);
        const S128 cy = crossTerm(b.z, c.x, b.x, c.z);
        const S128 cz = crossTerm(b.x, c.y, b.y, c.x);
        return AddS128(AddS128(MulS128S64(cx, a.x.Raw()), MulS128S64(cy, a.y.Raw())), MulS128S64(cz, a.z.Raw()));
    }
};

/// A * v, each component an exact sum rounded once.
constexpr b2Vec3 b2Mul(const b2Mat33& A, const b2Vec3& v) noexcept {
    auto row = [&](Fixed a, Fixed b, Fixed c) {
        const detail::S128 s = detail::Dot3Exact(a.Raw(), v.x.Raw(), b.Raw(), v.y.Raw(), c.Raw(), v.z.Raw());
        return Wide::FromRaw(detail::NarrowWide(s, "b2Mul(b2Mat33)", 0, 0)).ToFixed();
    };
    return {row(A.ex.x, A.ey.x, A.ez.x), row(A.ex.y, A.ey.y, A.ez.y), row(A.ex.z, A.ey.z, A.ez.z)};
}
/// The upper 2x2 block times v.
constexpr b2Vec2 b2Mul22(const b2Mat33& A, const b2Vec2& v) noexcept {
    return b2Mul(b2Mat22(A.ex.x, A.ey.x, A.ex.y, A.ey.y), v);
}

}  // namespace lockbox
