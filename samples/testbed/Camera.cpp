// The camera's screen/world mapping (display only) and the one documented rounding helper.
#include "Camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <GL/gl.h>

namespace lockbox::testbed {

b2Vec2 RoundDisplayToFixed(const ViewPoint& p) noexcept {
    // Round to nearest, ties away from zero (std::lround), on the 1/65536 m grid; clamp to the
    // symmetric Q16.16 range so a pointer far off screen cannot wrap around.
    auto round = [](double metres) {
        const double scaled = metres * static_cast<double>(Fixed::kOneRaw);
        const double limit = static_cast<double>(Fixed::kMaxRaw);
        const double clamped = std::clamp(scaled, -limit, limit);
        return Fixed::FromRaw(static_cast<int32_t>(std::lround(clamped)));
    };
    return b2Vec2(round(p.x), round(p.y));
}

double Camera::HalfWidth(const Viewport& vp) const noexcept {
    return halfHeight * static_cast<double>(vp.width) / static_cast<double>(std::max(vp.height, 1));
}

double Camera::MetresPerPixel(const Viewport& vp) const noexcept {
    return 2.0 * halfHeight / static_cast<double>(std::max(vp.height, 1));
}

ViewPoint Camera::ScreenToWorld(const Viewport& vp, double px, double py) const noexcept {
    const double k = MetresPerPixel(vp);
    // Window y grows downwards, world y upwards.
    return ViewPoint{center.x + (px - vp.x - 0.5 * vp.width) * k, center.y - (py - vp.y - 0.5 * vp.height) * k};
}

void Camera::PanPixels(const Viewport& vp, double dxPixels, double dyPixels) noexcept {
    const double k = MetresPerPixel(vp);
    center.x -= dxPixels * k;
    center.y += dyPixels * k;
}

void Camera::ZoomAt(const Viewport& vp, double px, double py, double factor) noexcept {
    const ViewPoint before = ScreenToWorld(vp, px, py);
    // Keep the zoom within what Q16.16 worlds can show: a millimetre to the world bounds.
    halfHeight = std::clamp(halfHeight * factor, 0.001, 20000.0);
    const ViewPoint after = ScreenToWorld(vp, px, py);
    center.x += before.x - after.x;
    center.y += before.y - after.y;
}

void Camera::Fit(const Viewport& vp, double x0, double y0, double x1, double y1) noexcept {
    const double margin = 0.08 * std::max(x1 - x0, y1 - y0) + 0.5;
    x0 -= margin, x1 += margin, y0 -= margin, y1 += margin;
    center = ViewPoint{0.5 * (x0 + x1), 0.5 * (y0 + y1)};
    const double aspect = static_cast<double>(vp.width) / static_cast<double>(std::max(vp.height, 1));
    halfHeight = std::max(0.5 * (y1 - y0), 0.5 * (x1 - x0) / aspect);
}

void Camera::Apply(const Viewport& vp, int windowHeight, float scale) const {
    auto px = [scale](int v) { return static_cast<GLint>(static_cast<float>(v) * scale + 0.5f); };
    const GLint x = px(vp.x), y = px(windowHeight - vp.y - vp.height);
    glViewport(x, y, px(vp.width), px(vp.height));
    // The scissor box keeps the clear and the drawing of one view out of the other.
    glScissor(x, y, px(vp.width), px(vp.height));
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    const double hw = HalfWidth(vp);
    glOrtho(center.x - hw, center.x + hw, center.y - halfHeight, center.y + halfHeight, -1.0, 1.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

namespace {

struct Box {
    double x0 = std::numeric_limits<double>::max(), y0 = x0;
    double x1 = -std::numeric_limits<double>::max(), y1 = x1;
    bool Empty() const noexcept { return x1 < x0; }
    void Add(double ax0, double ay0, double ax1, double ay1) noexcept {
        x0 = std::min(x0, ax0), y0 = std::min(y0, ay0), x1 = std::max(x1, ax1), y1 = std::max(y1, ay1);
    }
};

// Calls f(x0, y0, x1, y1) for every broad-phase AABB of a body's fixtures (display doubles).
template <class F>
void ForEachAabb(b2Body* body, F&& f) {
    for (b2Fixture* fx = body->GetFixtureList(); fx; fx = fx->GetNext())
        for (int32 i = 0; i < fx->GetProxyCount(); ++i) {
            const b2AABB& a = fx->GetAABB(i);
            f(a.lowerBound.x.ToDouble(), a.lowerBound.y.ToDouble(), a.upperBound.x.ToDouble(),
              a.upperBound.y.ToDouble());
        }
}

}  // namespace

void FitWorld(Camera& camera, const Viewport& vp, b2World& world) {
    Box moving, fixed;
    for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        Box& into = b->GetType() == b2_staticBody ? fixed : moving;
        ForEachAabb(b, [&](double x0, double y0, double x1, double y1) { into.Add(x0, y0, x1, y1); });
    }
    if (moving.Empty()) {
        if (fixed.Empty()) return;
        camera.Fit(vp, fixed.x0, fixed.y0, fixed.x1, fixed.y1);
        return;
    }
    // Static geometry near the moving bodies (ground under a stack) joins the view, clipped to
    // the moving bodies' box grown by half its size on each side.
    const double gx = 0.5 * (moving.x1 - moving.x0) + 2, gy = 0.5 * (moving.y1 - moving.y0) + 2;
    Box view = moving;
    for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() != b2_staticBody) continue;
        ForEachAabb(b, [&](double x0, double y0, double x1, double y1) {
            const double cx0 = std::max(x0, moving.x0 - gx), cx1 = std::min(x1, moving.x1 + gx);
            const double cy0 = std::max(y0, moving.y0 - gy), cy1 = std::min(y1, moving.y1 + gy);
            if (cx0 <= cx1 && cy0 <= cy1) view.Add(cx0, cy0, cx1, cy1);
        });
    }
    camera.Fit(vp, view.x0, view.y0, view.x1, view.y1);
}

}  // namespace lockbox::testbed
