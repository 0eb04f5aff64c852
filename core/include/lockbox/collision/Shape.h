#pragma once
/// @file
/// b2Shape (the manual's "Shapes" chapter): the abstract collision shape, its mass data and the
/// validation errors shared by every concrete shape.
///
/// Differences from Box2D 2.2.1, all deliberate:
/// - Mass and rotational inertia are Wide (Q32.32): in Q16.16 it
///   underflows the inertia of a 0.1 m box and overflows the inertia of a 10 m box at density 10.
/// - Clone() returns a std::unique_ptr: lockbox has no block allocator.
/// - Setters that can receive invalid geometry (polygon Set/SetAsBox/SetFromHull, chain
///   CreateChain/CreateLoop, edge Set, circle Set) return a b2ShapeError. On any error the shape
///   is left exactly as it was; nothing is half-built. Ignoring the return value still compiles,
///   so the manual's snippets work unchanged.

#include <memory>

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

/// Why a shape setter refused its input. `ok` (0) means the shape was set.
enum class b2ShapeError : uint8 {
    ok = 0,             ///< accepted
    tooFewVertices,     ///< polygon < 3 points, chain < 2, loop < 3
    tooManyVertices,    ///< polygon > b2_maxPolygonVertices (8) points (or hull vertices)
    duplicateVertices,  ///< two points closer than the weld distance (see b2_polygonWeldDistance)
    collinear,          ///< all points on one line, or a vertex within the weld distance of its
                        ///< neighbours' chord (a redundant vertex)
    notConvex,          ///< a vertex lies on the outer side of an edge
    clockwise,          ///< convex but wound clockwise; Set wants counter-clockwise
    areaTooSmall,       ///< area below b2_minPolygonArea: the inertia would be meaningless
    nonPositiveExtent,  ///< SetAsBox half-width or half-height <= 0
    nonPositiveRadius,  ///< circle radius <= 0
    outOfRange,         ///< a coordinate (or |centre| + radius) beyond b2_maxShapeCoordinate
};

/// A short English description of `error` ("ok" for ok). Never null; static storage.
LOCKBOX_API const char* b2ShapeErrorMessage(b2ShapeError error) noexcept;

/// Largest |x| or |y| of any shape vertex, centre or circle extent, in the body frame (m, raw
/// 2^28). Why 4096 m: it keeps every polygon mass sum exact in 128 bits (edges < 2^29 raw, the
/// quartic inertia terms < 2^123), far beyond any body a game builds.
inline constexpr Fixed b2_maxShapeCoordinate = 4096;

/// Minimum distance between two polygon vertices, and minimum distance of a polygon vertex from
/// the chord of its two neighbours (m, raw 164 = linearSlop / 2 rounded up). Box2D 2.3+ welds
/// polygon points closer than 0.5 * linearSlop; a feature smaller than that is below what the
/// contact solver resolves (it tolerates linearSlop of overlap), and its edge normal would be
/// set by rounding (direction error ~0.5 raw / 164 raw = 3e-3 rad).
inline constexpr Fixed b2_polygonWeldDistance = Fixed::FromRaw(164);

/// Minimum distance between consecutive chain (and edge) vertices (m, raw 328 = linearSlop), as
/// Box2D 2.3+ asserts: a shorter segment has no stable normal at the contact scale.
inline constexpr Fixed b2_chainWeldDistance = b2_linearSlop;

/// Minimum polygon area (m^2, 2^-10 = 9.77e-4, a 3.1 cm square). Derivation: every planar
/// shape of area A has a polar moment about its centroid of at least A^2 / (2 pi) (the disc is
/// the minimum). At A = 2^-10 and the lowest density of the documented envelope (0.1 kg/m^2)
/// that is I >= 1.5e-8 kg m^2 = 65 Q32.32 ULP, so I is carried to within 1 % and 1/I fits
/// Wide. Any smaller polygon may get I = 0 or an overflowing 1/I.
inline constexpr Wide b2_minPolygonArea = Wide::FromRaw(int64_t{1} << 22);

/// Mass properties of a shape, computed from its density.
struct b2MassData {
    Wide mass;      ///< kg (Q32.32); 0 for edges and chains
    b2Vec2 center;  ///< centre of mass relative to the body origin, m
    Wide I;         ///< rotational inertia about the body origin (not the centroid), kg m^2
};

/// The abstract shape. Concrete shapes: b2CircleShape, b2EdgeShape, b2PolygonShape,
/// b2ChainShape. Shapes are plain copyable values; a fixture owns a Clone().
class LOCKBOX_API b2Shape {
public:
    /// Shape kinds; the values match Box2D 2.2.1 (they index the contact registers).
    enum Type { e_circle = 0, e_edge = 1, e_polygon = 2, e_chain = 3, e_typeCount = 4 };

    virtual ~b2Shape() = default;

    /// A heap copy of this shape with the same dynamic type.
    virtual std::unique_ptr<b2Shape> Clone() const = 0;

    /// The kind of shape; use it to downcast.
    Type GetType() const noexcept { return m_type; }

    /// Number of child primitives: 1, except a chain (its edge count).
    virtual int32 GetChildCount() const = 0;

    /// True when point p (world frame, m) is inside the shape placed at xf. Boundary points
    /// count as inside. Edges and chains have no interior and always return false.
    virtual bool TestPoint(const b2Transform& xf, const b2Vec2& p) const = 0;

    /// Casts a ray against child `childIndex` placed at `transform`. Returns true on a hit at
    /// fraction in [0, input.maxFraction] with the outward unit surface normal (world frame).
    /// A ray that starts inside a circle or polygon does not hit it.
    virtual bool RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& transform,
                         int32 childIndex) const = 0;

    /// The world AABB of child `childIndex` placed at xf, including the shape radius.
    virtual void ComputeAABB(b2AABB* aabb, const b2Transform& xf, int32 childIndex) const = 0;

    /// Mass, centre and rotational inertia (about the body origin) for `density` (kg/m^2, >= 0).
    /// Results beyond the Wide range saturate (or trap in checked builds).
    virtual void ComputeMass(b2MassData* massData, Fixed density) const = 0;

    Type m_type;     ///< the concrete kind
    Fixed m_radius;  ///< circle radius, or the skin radius of polygons, edges and chains (m)

protected:
    /// A shape of the given type and radius (m); for the concrete shapes to call.
    b2Shape(Type type, Fixed radius) noexcept : m_type(type), m_radius(radius) {}
    /// Copying is for the concrete shapes (b2Fixture clones its shape through them); a b2Shape is
    /// never copied on its own, which would slice it.
    ///@{
    b2Shape(const b2Shape&) = default;
    b2Shape& operator=(const b2Shape&) = default;
    ///@}
};

}  // namespace lockbox
