#pragma once
/// @file
/// b2CircleShape: a solid circle given by a centre in the body frame and a radius.

#include <memory>

#include "lockbox/Export.h"
#include "lockbox/collision/Shape.h"

namespace lockbox {

/// A solid circle. The manual's style (`circle.m_p.Set(...); circle.m_radius = r;`) still works;
/// Set() and the radius constructor additionally validate.
class LOCKBOX_API b2CircleShape : public b2Shape {
public:
    /// A zero-radius circle at the origin (as Box2D; give it a radius before use).
    b2CircleShape() noexcept : b2Shape(e_circle, Fixed()) {}

    /// A circle of `radius` (m, > 0) centred at `center` (body frame). On invalid input the
    /// shape stays the default zero circle and `*error` (when given) receives the reason;
    /// prefer Set() when the input is untrusted.
    explicit b2CircleShape(Fixed radius, const b2Vec2& center = b2Vec2(), b2ShapeError* error = nullptr) noexcept;

    /// Sets centre and radius. Rejects radius <= 0 (nonPositiveRadius) and
    /// |center.x| + radius or |center.y| + radius beyond b2_maxShapeCoordinate (outOfRange);
    /// on error the shape is unchanged.
    b2ShapeError Set(const b2Vec2& center, Fixed radius) noexcept;

    /// Sets the radius only, with the same checks as Set().
    b2ShapeError SetRadius(Fixed radius) noexcept { return Set(m_p, radius); }

    std::unique_ptr<b2Shape> Clone() const override;
    int32 GetChildCount() const override { return 1; }
    /// Inside when |p - centre|^2 <= r^2, compared exactly.
    bool TestPoint(const b2Transform& transform, const b2Vec2& p) const override;
    /// Exact quadratic in 128 bits (the discriminant is L^4); no hit when p1 is inside.
    bool RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& transform,
                 int32 childIndex) const override;
    void ComputeAABB(b2AABB* aabb, const b2Transform& transform, int32 childIndex) const override;
    /// mass = density * pi * r^2, I = mass * (r^2 / 2 + |p|^2); pi carried to 2^-32.
    void ComputeMass(b2MassData* massData, Fixed density) const override;

    /// Index of the support vertex in direction d: always 0.
    int32 GetSupport(const b2Vec2& d) const noexcept {
        (void)d;
        return 0;
    }
    /// The support vertex in direction d: the centre.
    const b2Vec2& GetSupportVertex(const b2Vec2& d) const noexcept {
        (void)d;
        return m_p;
    }
    /// A circle has one vertex (its centre) for the distance routines.
    int32 GetVertexCount() const noexcept { return 1; }
    /// The centre; index must be 0.
    const b2Vec2& GetVertex(int32 index) const noexcept {
        (void)index;
        return m_p;
    }

    b2Vec2 m_p;  ///< centre in the body frame, m
};

}  // namespace lockbox
