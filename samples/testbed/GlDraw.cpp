// GlDraw: b2Draw into two vertex batches drawn with client-side arrays (OpenGL 1.1).
#include "GlDraw.h"

#include <cmath>
#include <cstddef>

#include <GL/gl.h>

namespace lockbox::testbed {

namespace {

// Circles are drawn as 24-sided polygons: round enough at any zoom for debug drawing.
constexpr int kCircleSegments = 24;
constexpr float kTwoPi = 6.28318530718f;
// Fills are the outline colour at half intensity and half opacity, so outlines stay readable
// where bodies overlap (the look of Box2D's testbed).
constexpr float kFillScale = 0.5f;
constexpr float kFillAlpha = 0.5f;

b2Color Scaled(const b2Color& c, float k) { return b2Color(c.r * k, c.g * k, c.b * k); }

}  // namespace

void GlDraw::Triangle(float ax, float ay, float bx, float by, float cx, float cy, const b2Color& c, float alpha) {
    triangles_.push_back({ax, ay, c.r, c.g, c.b, alpha});
    triangles_.push_back({bx, by, c.r, c.g, c.b, alpha});
    triangles_.push_back({cx, cy, c.r, c.g, c.b, alpha});
}

void GlDraw::Line(float x1, float y1, float x2, float y2, const b2Color& color, float alpha) {
    lines_.push_back({x1, y1, color.r, color.g, color.b, alpha});
    lines_.push_back({x2, y2, color.r, color.g, color.b, alpha});
}

void GlDraw::Point(float x, float y, float size, const b2Color& color) {
    const float h = 0.5f * size;
    Triangle(x - h, y - h, x + h, y - h, x + h, y + h, color, 1.0f);
    Triangle(x - h, y - h, x + h, y + h, x - h, y + h, color, 1.0f);
}

void GlDraw::DrawPolygon(const b2Vec2* vertices, int32 vertexCount, const b2Color& color) {
    for (int32 i = 0; i < vertexCount; ++i) {
        const b2Vec2& a = vertices[i];
        const b2Vec2& b = vertices[(i + 1) % vertexCount];
        Line(a.x.ToFloat(), a.y.ToFloat(), b.x.ToFloat(), b.y.ToFloat(), color);
    }
}

void GlDraw::DrawSolidPolygon(const b2Vec2* vertices, int32 vertexCount, const b2Color& color) {
    // Polygons are convex: a fan from the first vertex covers them.
    const b2Color fill = Scaled(color, kFillScale);
    const float x0 = vertices[0].x.ToFloat(), y0 = vertices[0].y.ToFloat();
    for (int32 i = 1; i + 1 < vertexCount; ++i)
        Triangle(x0, y0, vertices[i].x.ToFloat(), vertices[i].y.ToFloat(), vertices[i + 1].x.ToFloat(),
                 vertices[i + 1].y.ToFloat(), fill, kFillAlpha);
    DrawPolygon(vertices, vertexCount, color);
}

void GlDraw::DrawCircle(const b2Vec2& center, Fixed radius, const b2Color& color) {
    const float cx = center.x.ToFloat(), cy = center.y.ToFloat(), r = radius.ToFloat();
    float px = cx + r, py = cy;
    for (int i = 1; i <= kCircleSegments; ++i) {
        const float t = kTwoPi * static_cast<float>(i) / kCircleSegments;
        const float x = cx + r * std::cos(t), y = cy + r * std::sin(t);
        Line(px, py, x, y, color);
        px = x, py = y;
    }
}

void GlDraw::DrawSolidCircle(const b2Vec2& center, Fixed radius, const b2Vec2& axis, const b2Color& color) {
    const float cx = center.x.ToFloat(), cy = center.y.ToFloat(), r = radius.ToFloat();
    const b2Color fill = Scaled(color, kFillScale);
    float px = cx + r, py = cy;
    for (int i = 1; i <= kCircleSegments; ++i) {
        const float t = kTwoPi * static_cast<float>(i) / kCircleSegments;
        const float x = cx + r * std::cos(t), y = cy + r * std::sin(t);
        Triangle(cx, cy, px, py, x, y, fill, kFillAlpha);
        px = x, py = y;
    }
    DrawCircle(center, radius, color);
    // The axis line shows the rotation of a circle.
    Line(cx, cy, cx + r * axis.x.ToFloat(), cy + r * axis.y.ToFloat(), color);
}

void GlDraw::DrawSegment(const b2Vec2& p1, const b2Vec2& p2, const b2Color& color) {
    Line(p1.x.ToFloat(), p1.y.ToFloat(), p2.x.ToFloat(), p2.y.ToFloat(), color);
}

void GlDraw::DrawTransform(const b2Transform& xf) {
    // Unit axes shortened to 0.4 m: red along x, green along y.
    constexpr float kAxis = 0.4f;
    const float x = xf.p.x.ToFloat(), y = xf.p.y.ToFloat();
    const float c = xf.q.c.ToFloat(), s = xf.q.s.ToFloat();
    Line(x, y, x + kAxis * c, y + kAxis * s, b2Color(1, 0, 0));
    Line(x, y, x - kAxis * s, y + kAxis * c, b2Color(0, 1, 0));
}

void GlDraw::DrawBatch(const std::vector<Vertex>& batch, unsigned mode) {
    if (batch.empty()) return;
    glVertexPointer(2, GL_FLOAT, sizeof(Vertex), &batch[0].x);
    glColorPointer(4, GL_FLOAT, sizeof(Vertex), &batch[0].r);
    glDrawArrays(mode, 0, static_cast<GLsizei>(batch.size()));
}

void GlDraw::Flush() {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    DrawBatch(triangles_, GL_TRIANGLES);
    DrawBatch(lines_, GL_LINES);
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    triangles_.clear();
    lines_.clear();
}

}  // namespace lockbox::testbed
