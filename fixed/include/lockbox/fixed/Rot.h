#pragma once
/// @file
/// b2Rot (the manual's Math module): a rotation stored as its sine and cosine.

#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/Vec2.h"

namespace lockbox {

/// A rotation stored as its sine and cosine (Q16.16, each within 1 ULP of the exact value), so that
/// rotating a vector needs no trigonometry. The default is the identity (angle 0).
struct b2Rot {
    Fixed s;      ///< sine
    Fixed c = 1;  ///< cosine

    /// The identity rotation.
    constexpr b2Rot() noexcept = default;
    /// From an angle in radians (any value; sin and cos are within 1 ULP).
    explicit b2Rot(Fixed angle) noexcept { Set(angle); }

    /// Sets the rotation to `angle` radians (any value; it is reduced modulo 2 pi).
    void Set(Fixed angle) noexcept { math::SinCos(angle, s, c); }
    /// Sets the identity rotation (s = 0, c = 1).
    constexpr void SetIdentity() noexcept {
        s = 0;
        c = 1;
    }
    /// The angle in radians, in [-pi, pi].
    Fixed GetAngle() const noexcept { return math::Atan2(s, c); }
    /// The rotated x axis (c, s): the first column of the rotation matrix.
    constexpr b2Vec2 GetXAxis() const noexcept { return {c, s}; }
    /// The rotated y axis (-s, c): the second column of the rotation matrix.
    constexpr b2Vec2 GetYAxis() const noexcept { return {-s, c}; }
};

/// q * r: rotate by r, then by q. Each component is an exact sum rounded once.
constexpr b2Rot b2Mul(const b2Rot& q, const b2Rot& r) noexcept {
    b2Rot qr;
    qr.s = Wide::FromRaw(detail::SumOfProducts(q.s.Raw(), r.c.Raw(), q.c.Raw(), r.s.Raw())).ToFixed();
    qr.c = Wide::FromRaw(detail::DiffOfProducts(q.c.Raw(), r.c.Raw(), q.s.Raw(), r.s.Raw())).ToFixed();
    return qr;
}
/// transpose(q) * r: rotate by r, then by the inverse of q.
constexpr b2Rot b2MulT(const b2Rot& q, const b2Rot& r) noexcept {
    b2Rot qr;
    qr.s = Wide::FromRaw(detail::DiffOfProducts(q.c.Raw(), r.s.Raw(), q.s.Raw(), r.c.Raw())).ToFixed();
    qr.c = Wide::FromRaw(detail::SumOfProducts(q.c.Raw(), r.c.Raw(), q.s.Raw(), r.s.Raw())).ToFixed();
    return qr;
}
/// Rotates a vector.
constexpr b2Vec2 b2Mul(const b2Rot& q, const b2Vec2& v) noexcept {
    return {Wide::FromRaw(detail::DiffOfProducts(q.c.Raw(), v.x.Raw(), q.s.Raw(), v.y.Raw())).ToFixed(),
            Wide::FromRaw(detail::SumOfProducts(q.s.Raw(), v.x.Raw(), q.c.Raw(), v.y.Raw())).ToFixed()};
}
/// Inverse-rotates a vector.
constexpr b2Vec2 b2MulT(const b2Rot& q, const b2Vec2& v) noexcept {
    return {Wide::FromRaw(detail::SumOfProducts(q.c.Raw(), v.x.Raw(), q.s.Raw(), v.y.Raw())).ToFixed(),
            Wide::FromRaw(detail::DiffOfProducts(q.c.Raw(), v.y.Raw(), q.s.Raw(), v.x.Raw())).ToFixed()};
}

}  // namespace lockbox
