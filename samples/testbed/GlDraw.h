#pragma once
/// GlDraw: lockbox's b2Draw on legacy OpenGL. Every call appends coloured vertices to one of
/// two batches (triangles, lines) and Flush draws each batch with a single glDrawArrays, so a
/// 10000-body scene costs two draw calls instead of thousands of glBegin/glEnd pairs.
///
/// Coordinates arrive as Fixed and are turned into float here with ToFloat(): display only,
/// nothing flows back into a world.

#include <vector>

#include "lockbox/lockbox.h"

namespace lockbox::testbed {

/// Debug draw into vertex batches, drawn by Flush in the current GL projection.
class GlDraw : public b2Draw {
public:
    // The b2Draw interface (lockbox/dynamics/Draw.h): each call appends to a batch.
    /// An outline: one line pair per edge.
    void DrawPolygon(const b2Vec2* vertices, int32 vertexCount, const b2Color& color) override;
    /// A fan of translucent triangles under the outline.
    void DrawSolidPolygon(const b2Vec2* vertices, int32 vertexCount, const b2Color& color) override;
    /// A 24-sided outline.
    void DrawCircle(const b2Vec2& center, Fixed radius, const b2Color& color) override;
    /// A filled 24-sided polygon with its outline and the axis line.
    void DrawSolidCircle(const b2Vec2& center, Fixed radius, const b2Vec2& axis, const b2Color& color) override;
    /// One line.
    void DrawSegment(const b2Vec2& p1, const b2Vec2& p2, const b2Color& color) override;
    /// The frame's axes, 0.4 m long: x red, y green.
    void DrawTransform(const b2Transform& xf) override;

    /// A line between display points (m), for overlays such as the mouse joint.
    void Line(float x1, float y1, float x2, float y2, const b2Color& color, float alpha = 1.0f);
    /// A filled square of side `size` m centred on a display point.
    void Point(float x, float y, float size, const b2Color& color);

    /// Draws and empties both batches (triangles first, outlines on top).
    void Flush();

private:
    struct Vertex {
        float x, y;
        float r, g, b, a;
    };
    void Triangle(float ax, float ay, float bx, float by, float cx, float cy, const b2Color& c, float alpha);
    static void DrawBatch(const std::vector<Vertex>& batch, unsigned mode);

    std::vector<Vertex> triangles_;
    std::vector<Vertex> lines_;
};

}  // namespace lockbox::testbed
