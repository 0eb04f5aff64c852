#pragma once
/// @file
/// Q32.32 vectors: impulses (N*s) and wide velocities (m/s), for the contact and joint solvers,
/// whose accumulated impulses and inverse-mass responses do not fit Q16.16 (docs/numerics.md, "Formats").

#include <concepts>

#include "lockbox/fixed/Vec2.h"
#include "lockbox/fixed/Vec3.h"
#include "lockbox/fixed/Wide.h"

namespace lockbox {

/// A 2D vector in Q32.32: an impulse (N*s) or a wide velocity (m/s).
struct b2WideVec2 {
    /// The components as Q32.32 (N*s for an impulse, m/s for a velocity).
    ///@{
    Wide x;
    Wide y;
    ///@}

    /// Zero, or from components (Q32.32).
    constexpr b2WideVec2() noexcept = default;
    /// Zero, or from components (Q32.32).
    constexpr b2WideVec2(Wide xIn, Wide yIn) noexcept : x(xIn), y(yIn) {}
    /// Exact widening of a Q16.16 vector.
    constexpr explicit b2WideVec2(const b2Vec2& v) noexcept : x(Wide(v.x)), y(Wide(v.y)) {}

    /// Sets all components to zero.
    constexpr void SetZero() noexcept {
        x = Wide();
        y = Wide();
    }
    /// Component-wise arithmetic (saturating Wide operations).
    constexpr b2WideVec2 operator-() const noexcept { return {-x, -y}; }
    /// Component-wise arithmetic (saturating Wide operations).
    constexpr b2WideVec2& operator+=(const b2WideVec2& v) noexcept {
        x += v.x;
        y += v.y;
        return *this;
    }
    /// Component-wise arithmetic (saturating Wide operations).
    constexpr b2WideVec2& operator-=(const b2WideVec2& v) noexcept {
        x -= v.x;
        y -= v.y;
        return *this;
    }
    /// Squared length (Q32.32, rounded once; saturates beyond 46341). b2ClampLength compares
    /// exact 128-bit squares instead.
    constexpr Wide LengthSquared() const noexcept { return x * x + y * y; }
    /// Rounds to a Q16.16 vector (saturating).
    constexpr b2Vec2 ToFixed() const noexcept { return {x.ToFixed(), y.ToFixed()}; }
};

/// Component-wise arithmetic (saturating Wide operations).
constexpr b2WideVec2 operator+(const b2WideVec2& a, const b2WideVec2& b) noexcept { return {a.x + b.x, a.y + b.y}; }
/// Component-wise arithmetic (saturating Wide operations).
constexpr b2WideVec2 operator-(const b2WideVec2& a, const b2WideVec2& b) noexcept { return {a.x - b.x, a.y - b.y}; }
// The scalar of a product takes the type of the vector's components when it is a plain number:
// `2 * v` is Fixed(2) * v for a b2Vec2 and Wide(2) * v for a b2WideVec2. The mixed overloads
// below are templates so that a number, which converts to both Fixed and Wide, never selects
// them (as Wide * Fixed in Wide.h).

/// s * v with a Q16.16 scalar, one rounding per component.
template <std::same_as<Fixed> F>
constexpr b2WideVec2 operator*(F s, const b2WideVec2& v) noexcept {
    return {v.x * s, v.y * s};
}
/// s * v with a Q32.32 scalar, one rounding per component.
constexpr b2WideVec2 operator*(Wide s, const b2WideVec2& v) noexcept { return {s * v.x, s * v.y}; }
/// s * d for a Q16.16 vector d (an impulse along a direction), one rounding per component.
template <std::same_as<Wide> W>
constexpr b2WideVec2 operator*(W s, const b2Vec2& d) noexcept {
    return {s * d.x, s * d.y};
}

/// A 3D vector in Q32.32 (point impulse plus angular impulse).
struct b2WideVec3 {
    /// The components as Q32.32 (x and y linear, z angular).
    ///@{
    Wide x;
    Wide y;
    Wide z;
    ///@}

    /// Zero, or from components (Q32.32).
    constexpr b2WideVec3() noexcept = default;
    /// Zero, or from components (Q32.32).
    constexpr b2WideVec3(Wide xIn, Wide yIn, Wide zIn) noexcept : x(xIn), y(yIn), z(zIn) {}
    /// Exact widening of a Q16.16 vector.
    constexpr explicit b2WideVec3(const b2Vec3& v) noexcept : x(Wide(v.x)), y(Wide(v.y)), z(Wide(v.z)) {}

    /// Sets all components to zero.
    constexpr void SetZero() noexcept { x = y = z = Wide(); }
    /// Component-wise arithmetic (saturating Wide operations).
    constexpr b2WideVec3 operator-() const noexcept { return {-x, -y, -z}; }
    /// Component-wise arithmetic (saturating Wide operations).
    constexpr b2WideVec3& operator+=(const b2WideVec3& v) noexcept {
        x += v.x;
        y += v.y;
        z += v.z;
        return *this;
    }
    /// Component-wise arithmetic (saturating Wide operations).
    constexpr b2WideVec3& operator-=(const b2WideVec3& v) noexcept {
        x -= v.x;
        y -= v.y;
        z -= v.z;
        return *this;
    }
};

/// Component-wise arithmetic (saturating Wide operations).
constexpr b2WideVec3 operator+(const b2WideVec3& a, const b2WideVec3& b) noexcept {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
/// Component-wise arithmetic (saturating Wide operations).
constexpr b2WideVec3 operator-(const b2WideVec3& a, const b2WideVec3& b) noexcept {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}

}  // namespace lockbox
