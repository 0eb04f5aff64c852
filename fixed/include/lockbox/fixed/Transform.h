#pragma once
/// b2Transform (the manual's Math module): a translation and a rotation, the frame of a body.

#include "lockbox/fixed/Rot.h"

namespace lockbox {

struct b2Transform {
    b2Vec2 p;  ///< translation, metres
    b2Rot q;   ///< rotation

    /// The identity transform.
    constexpr b2Transform() noexcept = default;
    constexpr b2Transform(const b2Vec2& position, const b2Rot& rotation) noexcept : p(position), q(rotation) {}

    constexpr void SetIdentity() noexcept { p.SetZero(); q.SetIdentity(); }
    void Set(const b2Vec2& position, Fixed angle) noexcept { p = position; q.Set(angle); }
};

namespace detail {
/// c1*a + c2*b + offset with the products exact and one rounding (offset is Q16.16).
constexpr Fixed RotateAndOffset(int64_t exactQ32, Fixed offset) noexcept {
    return (Wide::FromRaw(exactQ32) + Wide(offset)).ToFixed();
}
}  // namespace detail

/// T * v: rotate then translate; each component is rounded once.
constexpr b2Vec2 b2Mul(const b2Transform& T, const b2Vec2& v) noexcept {
    const b2Rot& q = T.q;
    return {detail::RotateAndOffset(detail::DiffOfProducts(q.c.Raw(), v.x.Raw(), q.s.Raw(), v.y.Raw()), T.p.x),
            detail::RotateAndOffset(detail::SumOfProducts(q.s.Raw(), v.x.Raw(), q.c.Raw(), v.y.Raw()), T.p.y)};
}
/// inverse(T) * v.
constexpr b2Vec2 b2MulT(const b2Transform& T, const b2Vec2& v) noexcept { return b2MulT(T.q, v - T.p); }
/// A * B: the frame B expressed through A.
constexpr b2Transform b2Mul(const b2Transform& A, const b2Transform& B) noexcept {
    return {b2Mul(A.q, B.p) + A.p, b2Mul(A.q, B.q)};
}
/// inverse(A) * B.
constexpr b2Transform b2MulT(const b2Transform& A, const b2Transform& B) noexcept {
    return {b2MulT(A.q, B.p - A.p), b2MulT(A.q, B.q)};
}

}  // namespace lockbox
