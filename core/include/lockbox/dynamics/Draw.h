#pragma once
/// @file
/// b2Draw (Box2D 2.2.1 b2Draw.h): the debug-draw interface. Colours are floats because they are
/// display data only; coordinates stay Fixed and an implementation converts them with
/// ToFloat() for rendering. Nothing drawn ever flows back into the simulation.

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

/// An RGB colour in [0, 1] (display only).
struct b2Color {
    b2Color() = default;
    /// A colour from red, green and blue components in [0, 1].
    b2Color(float rIn, float gIn, float bIn) : r(rIn), g(gIn), b(bIn) {}
    /// Sets the red, green and blue components, each in [0, 1].
    void Set(float rIn, float gIn, float bIn) {
        r = rIn;
        g = gIn;
        b = bIn;
    }
    /// Red, green and blue intensity in [0, 1]. float: colours are for display only and never reach
    /// the simulation.
    ///@{
    float r = 0.0f;
    float g = 0.0f;
    float b = 0.0f;
    ///@}
};

/// Implement and register with b2World::SetDebugDraw to draw the world.
class LOCKBOX_API b2Draw {
public:
    virtual ~b2Draw() = default;

    enum : uint32 {
        e_shapeBit = 0x0001,         ///< draw shapes
        e_jointBit = 0x0002,         ///< draw joint connections
        e_aabbBit = 0x0004,          ///< draw the fat broad-phase AABBs
        e_pairBit = 0x0008,          ///< draw contact pairs (centre to centre)
        e_centerOfMassBit = 0x0010,  ///< draw the centre-of-mass frame
    };

    /// Sets the drawing flags.
    void SetFlags(uint32 flags) noexcept { m_drawFlags = flags; }
    /// The drawing flags (a combination of the e_*Bit values).
    uint32 GetFlags() const noexcept { return m_drawFlags; }
    /// Sets the given flags, keeping the others.
    void AppendFlags(uint32 flags) noexcept { m_drawFlags |= flags; }
    /// Clears the given flags, keeping the others.
    void ClearFlags(uint32 flags) noexcept { m_drawFlags &= ~flags; }

    /// A closed polygon outline (counter-clockwise vertices, m).
    virtual void DrawPolygon(const b2Vec2* vertices, int32 vertexCount, const b2Color& color) = 0;
    /// A filled polygon.
    virtual void DrawSolidPolygon(const b2Vec2* vertices, int32 vertexCount, const b2Color& color) = 0;
    /// A circle outline (centre and radius in m).
    virtual void DrawCircle(const b2Vec2& center, Fixed radius, const b2Color& color) = 0;
    /// A filled circle with an axis line.
    virtual void DrawSolidCircle(const b2Vec2& center, Fixed radius, const b2Vec2& axis, const b2Color& color) = 0;
    /// A line segment.
    virtual void DrawSegment(const b2Vec2& p1, const b2Vec2& p2, const b2Color& color) = 0;
    /// A frame (unit axes).
    virtual void DrawTransform(const b2Transform& xf) = 0;

protected:
    /// The drawing flags; b2World::DrawDebugData reads them through GetFlags.
    uint32 m_drawFlags = 0;
};

}  // namespace lockbox
