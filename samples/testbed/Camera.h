#pragma once
/// The testbed camera: a view centre and a zoom, mapping window pixels to world metres and back.
///
/// Everything here is display code, so it works in float/double. The one place where a screen
/// position becomes simulation input (the mouse joint target) goes through
/// RoundDisplayToFixed, the documented rounding helper below; no other float reaches a world.

#include <cstdint>

#include "lockbox/lockbox.h"

namespace lockbox::testbed {

/// A rectangle of the window in pixels, origin top-left (GLFW's cursor convention).
struct Viewport {
    int x = 0;       ///< left edge, px
    int y = 0;       ///< top edge, px
    int width = 1;   ///< px (> 0)
    int height = 1;  ///< px (> 0)

    /// True when the window pixel (px, py) lies inside.
    bool Contains(double px, double py) const noexcept {
        return px >= x && px < x + width && py >= y && py < y + height;
    }
};

/// A point in world metres, display precision (never fed to a world as is).
struct ViewPoint {
    double x = 0;
    double y = 0;
};

/// Rounds a display-side length in metres to the nearest Q16.16 value (ties away from zero),
/// saturating at the format's limits. This is the only float-to-Fixed path of the testbed: it
/// turns a mouse position into the mouse joint target, as Box2D's testbed does. The result
/// depends on the pointer position on screen, which is user input, so it is recorded nowhere
/// and the testbed does not pick bodies while it records a replay.
b2Vec2 RoundDisplayToFixed(const ViewPoint& p) noexcept;

/// Pan and zoom of the world view.
class Camera {
public:
    /// Centre of the view, m.
    ViewPoint center{0, 10};
    /// Half the height of the view, m (the zoom: smaller is closer).
    double halfHeight = 25;

    /// Half the width of the view in a viewport with the given aspect, m.
    double HalfWidth(const Viewport& vp) const noexcept;
    /// The world point under a window pixel of a viewport.
    ViewPoint ScreenToWorld(const Viewport& vp, double px, double py) const noexcept;
    /// Metres per pixel in a viewport.
    double MetresPerPixel(const Viewport& vp) const noexcept;
    /// Moves the view by a pixel delta (a drag: the world follows the pointer).
    void PanPixels(const Viewport& vp, double dxPixels, double dyPixels) noexcept;
    /// Zooms by a factor around a window pixel, keeping the world point under it in place.
    void ZoomAt(const Viewport& vp, double px, double py, double factor) noexcept;
    /// Shows the box [x0, x1] x [y0, y1] (m) with a margin, whatever the viewport's aspect.
    void Fit(const Viewport& vp, double x0, double y0, double x1, double y1) noexcept;
    /// Sets the GL viewport and projection (legacy matrices) for drawing world coordinates in
    /// a viewport of a window `windowHeight` pixels high whose framebuffer has `scale`
    /// framebuffer pixels per window pixel (GL's origin is bottom-left).
    void Apply(const Viewport& vp, int windowHeight, float scale) const;
};

/// Fits the camera to the bodies of a world: the fixture AABBs of the non-static bodies,
/// widened to include static fixtures that are not far larger than them (long ground edges
/// would otherwise shrink the scene to a line). An empty world keeps the camera.
void FitWorld(Camera& camera, const Viewport& vp, b2World& world);

}  // namespace lockbox::testbed
