#pragma once
/// @file
/// b2Vec3 (the manual's Math module): a 3D column vector, used by the 3x3 joint solves.

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Wide.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox {

/// A 3D column vector of Q16.16 components; the 3x3 block solvers of the weld, revolute and
/// prismatic joints use it for (linear x, linear y, angular) impulses and velocities.
struct b2Vec3 {
    /// The components; their unit is the quantity's (a joint's b2Vec3 impulse mixes N*s and N*m*s).
    ///@{
    Fixed x;
    Fixed y;
    Fixed z;
    ///@}

    constexpr b2Vec3() noexcept = default;
    /// The vector (xIn, yIn, zIn).
    constexpr b2Vec3(Fixed xIn, Fixed yIn, Fixed zIn) noexcept : x(xIn), y(yIn), z(zIn) {}

    /// Sets all three components to zero.
    constexpr void SetZero() noexcept { x = y = z = Fixed(); }
    /// Sets the components to (x_, y_, z_).
    constexpr void Set(Fixed x_, Fixed y_, Fixed z_) noexcept {
        x = x_;
        y = y_;
        z = z_;
    }

    /// The negated vector; each component saturates like Fixed's negation.
    constexpr b2Vec3 operator-() const noexcept { return {-x, -y, -z}; }
    /// In-place sum, difference and scaling by a scalar, component by component with Fixed's
    /// rounding and saturation.
    ///@{
    constexpr b2Vec3& operator+=(const b2Vec3& v) noexcept {
        x += v.x;
        y += v.y;
        z += v.z;
        return *this;
    }
    constexpr b2Vec3& operator-=(const b2Vec3& v) noexcept {
        x -= v.x;
        y -= v.y;
        z -= v.z;
        return *this;
    }
    constexpr b2Vec3& operator*=(Fixed s) noexcept {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    ///@}
};

/// Component-wise sum and difference, and scaling by a scalar (each product rounded once).
///@{
constexpr b2Vec3 operator+(const b2Vec3& a, const b2Vec3& b) noexcept { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr b2Vec3 operator-(const b2Vec3& a, const b2Vec3& b) noexcept { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr b2Vec3 operator*(Fixed s, const b2Vec3& a) noexcept { return {s * a.x, s * a.y, s * a.z}; }
///@}
/// Exact component-wise equality of the raw values.
constexpr bool operator==(const b2Vec3& a, const b2Vec3& b) noexcept { return a.x == b.x && a.y == b.y && a.z == b.z; }

namespace detail {
/// Exact a1*b1 + a2*b2 + a3*b3 of raw values as a 128-bit Q32.32.
constexpr S128 Dot3Exact(int32_t a1, int32_t b1, int32_t a2, int32_t b2, int32_t a3, int32_t b3) noexcept {
    return AddS128(AddS128(MulS64(a1, b1), MulS64(a2, b2)), MulS64(a3, b3));
}
}  // namespace detail

/// Dot product, exact sum rounded once.
constexpr Fixed b2Dot(const b2Vec3& a, const b2Vec3& b) noexcept {
    const detail::S128 d = detail::Dot3Exact(a.x.Raw(), b.x.Raw(), a.y.Raw(), b.y.Raw(), a.z.Raw(), b.z.Raw());
    const int64_t q32 = detail::NarrowWide(d, "b2Dot(b2Vec3)", a.x.Raw(), b.x.Raw());
    return Wide::FromRaw(q32).ToFixed();
}

/// Cross product; each component is an exact difference rounded once.
constexpr b2Vec3 b2Cross(const b2Vec3& a, const b2Vec3& b) noexcept {
    auto comp = [](Fixed p, Fixed q, Fixed r, Fixed s) {
        const int64_t v = int64_t{p.Raw()} * q.Raw();
        const int64_t w = int64_t{r.Raw()} * s.Raw();
        const detail::S128 d = detail::SubS128(detail::MulS64(v, 1), detail::MulS64(w, 1));
        return Wide::FromRaw(detail::NarrowWide(d, "b2Cross(b2Vec3)", v, w)).ToFixed();
    };
    return {comp(a.y, b.z, a.z, b.y), comp(a.z, b.x, a.x, b.z), comp(a.x, b.y, a.y, b.x)};
}

}  // namespace lockbox
