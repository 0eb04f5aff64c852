#pragma once
/// @file
/// b2Transform (the manual's Math module): a translation and a rotation, the frame of a body.

#include "lockbox/fixed/Rot.h"

namespace lockbox {

/// A rigid transform: a translation p (metres) and a rotation q. It maps a body's local coordinates
/// to world coordinates: world = q * local + p.
struct b2Transform {
    b2Vec2 p;  ///< translation, metres
    b2Rot q;   ///< rotation

    /// The identity transform.
    constexpr b2Transform() noexcept = default;
    /// The transform translating by `position` (metres) after rotating by `rotation`.
    constexpr b2Transform(const b2Vec2& position, const b2Rot& rotation) noexcept : p(position), q(rotation) {}

    /// Sets the identity transform (no translation, no rotation).
    constexpr void SetIdentity() noexcept {
        p.SetZero();
        q.SetIdentity();
    }
    /// Sets the translation (metres) and the rotation from an angle (radians).
    void Set(const b2Vec2& position, Fixed angle) noexcept {
        p = position;
        q.Set(angle);
    }
};

/// T * v: rotate (rounded once), then translate (exact). Rounding R v before adding p keeps
/// the result translation invariant: moving a scene by any offset moves every point by exactly
/// that offset. Rounding R v + p together would round ties by the sign of the world
/// coordinate, so a scene moved across an axis would drift by a raw (docs/stability.md).
constexpr b2Vec2 b2Mul(const b2Transform& T, const b2Vec2& v) noexcept { return b2Mul(T.q, v) + T.p; }
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
