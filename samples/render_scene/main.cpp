// render_scene: runs a lockbox scene for N steps and draws the frame through the world's
// b2Draw (DrawDebugData) into an SVG file, for the docs.
//
//   render_scene --scene NAME [--step N] [--velocity-iterations V] [--position-iterations P]
//                [--out FILE.svg] [--width PIXELS]
//
// Shapes, joints and centres of mass are drawn; the view fits everything drawn (scenes with
// far-away ground edges are clipped to the bodies' neighbourhood).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox;
using namespace lockbox::scenes;

namespace {

/// Collects b2Draw calls as SVG elements (y flipped: SVG's y grows downwards).
class SvgDraw : public b2Draw {
public:
    void DrawPolygon(const b2Vec2* v, int32 n, const b2Color& c) override { Poly(v, n, c, false); }
    void DrawSolidPolygon(const b2Vec2* v, int32 n, const b2Color& c) override { Poly(v, n, c, true); }
    void DrawCircle(const b2Vec2& center, Fixed radius, const b2Color& c) override { Circle(center, radius, c, false); }
    void DrawSolidCircle(const b2Vec2& center, Fixed radius, const b2Vec2& axis, const b2Color& c) override {
        Circle(center, radius, c, true);
        const double x = center.x.ToDouble(), y = center.y.ToDouble(), r = radius.ToDouble();
        Line(x, y, x + r * axis.x.ToDouble(), y + r * axis.y.ToDouble(), c);
    }
    void DrawSegment(const b2Vec2& p1, const b2Vec2& p2, const b2Color& c) override {
        Line(p1.x.ToDouble(), p1.y.ToDouble(), p2.x.ToDouble(), p2.y.ToDouble(), c);
        // Long static edges (ground) would shrink the picture: they do not widen the view.
    }
    void DrawTransform(const b2Transform& xf) override {
        const double x = xf.p.x.ToDouble(), y = xf.p.y.ToDouble();
        const double cx = xf.q.c.ToDouble(), sx = xf.q.s.ToDouble(), k = 0.2;
        Line(x, y, x + k * cx, y + k * sx, b2Color(1, 0, 0));
        Line(x, y, x - k * sx, y + k * cx, b2Color(0, 0.8f, 0));
    }

    /// Writes the SVG, viewing the bounds of everything but bare segments (plus a margin).
    bool Write(const std::string& path, int width, const std::string& title) const {
        double x0 = minX_, x1 = maxX_, y0 = minY_, y1 = maxY_;
        if (!(x1 > x0)) x0 = -10, x1 = 10;
        if (!(y1 > y0)) y0 = -10, y1 = 10;
        const double margin = 0.05 * std::max(x1 - x0, y1 - y0) + 0.5;
        x0 -= margin, x1 += margin, y0 -= margin, y1 += margin;
        const double scale = width / (x1 - x0);
        const int height = static_cast<int>(std::lround((y1 - y0) * scale));
        std::ofstream out(path);
        out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
            << "\" viewBox=\"" << x0 << " " << -y1 << " " << (x1 - x0) << " " << (y1 - y0) << "\">\n"
            << "<title>" << title << "</title>\n"
            << "<rect x=\"" << x0 << "\" y=\"" << -y1 << "\" width=\"" << (x1 - x0) << "\" height=\"" << (y1 - y0)
            << "\" fill=\"#1e1e23\"/>\n<g stroke-width=\"" << 1.2 / scale << "\">\n"
            << body_.str() << "</g>\n</svg>\n";
        return static_cast<bool>(out);
    }

private:
    static std::string Rgb(const b2Color& c, double k = 1) {
        char buf[32];
        auto ch = [k](float v) { return static_cast<int>(std::lround(std::clamp(v * k, 0.0, 1.0) * 255)); };
        std::snprintf(buf, sizeof buf, "#%02x%02x%02x", ch(c.r), ch(c.g), ch(c.b));
        return buf;
    }
    void Grow(double x, double y) {
        minX_ = std::min(minX_, x), maxX_ = std::max(maxX_, x);
        minY_ = std::min(minY_, y), maxY_ = std::max(maxY_, y);
    }
    void Poly(const b2Vec2* v, int32 n, const b2Color& c, bool solid) {
        body_ << "<polygon points=\"";
        for (int32 i = 0; i < n; ++i) {
            const double x = v[i].x.ToDouble(), y = v[i].y.ToDouble();
            body_ << x << "," << -y << " ";
            Grow(x, y);
        }
        body_ << "\" fill=\"" << (solid ? Rgb(c, 0.5) : "none") << "\" stroke=\"" << Rgb(c) << "\"/>\n";
    }
    void Circle(const b2Vec2& center, Fixed radius, const b2Color& c, bool solid) {
        const double x = center.x.ToDouble(), y = center.y.ToDouble(), r = radius.ToDouble();
        body_ << "<circle cx=\"" << x << "\" cy=\"" << -y << "\" r=\"" << r << "\" fill=\""
              << (solid ? Rgb(c, 0.5) : "none") << "\" stroke=\"" << Rgb(c) << "\"/>\n";
        Grow(x - r, y - r);
        Grow(x + r, y + r);
    }
    void Line(double xa, double ya, double xb, double yb, const b2Color& c) {
        body_ << "<line x1=\"" << xa << "\" y1=\"" << -ya << "\" x2=\"" << xb << "\" y2=\"" << -yb << "\" stroke=\""
              << Rgb(c) << "\"/>\n";
    }

    std::ostringstream body_;
    double minX_ = 1e30, maxX_ = -1e30, minY_ = 1e30, maxY_ = -1e30;
};

}  // namespace

int main(int argc, char** argv) {
    std::string name, out = "scene.svg";
    int steps = -1, width = 800;
    RunSettings s;
    constexpr const char* kUsage =
        "usage: render_scene --scene NAME [--step N] [--velocity-iterations V] [--position-iterations P]\n"
        "                    [--out FILE.svg] [--width PIXELS]\n";
    lockbox::cli::OptionReader args("render_scene", argc, argv);
    while (args.Next()) {
        if (args.Is("--scene"))
            args.Text(name);
        else if (args.Is("--step"))
            args.Int(-1, 100000000, steps);
        else if (args.Is("--out"))
            args.Text(out);
        else if (args.Is("--width"))
            args.Int(16, 16384, width);
        else if (args.Is("--velocity-iterations"))
            args.Int(-1, 1000, s.velocityIterations);
        else if (args.Is("--position-iterations"))
            args.Int(-1, 1000, s.positionIterations);
        else
            args.Unknown();
    }
    if (!args.Failed() && name.empty()) args.Refuse("give --scene NAME");
    if (args.Failed()) return args.Fail(kUsage);
    auto scene = MakeLockboxScene(name);
    if (!scene) {
        std::fprintf(stderr, "render_scene: unknown scene '%s'\n", name.c_str());
        return 2;
    }
    LockboxEngine e;
    s.steps = steps;
    s.trackMetrics = false;
    RunScene(e, *scene, s);
    SvgDraw draw;
    draw.SetFlags(b2Draw::e_shapeBit | b2Draw::e_jointBit);
    e.world().SetDebugDraw(&draw);
    e.world().DrawDebugData();
    e.world().SetDebugDraw(nullptr);
    const Resolved r = Resolve(scene->Info(), s);
    char title[256];
    std::snprintf(title, sizeof title, "%s on lockbox after %d steps, %d/%d iterations", name.c_str(), r.steps,
                  r.velocityIterations, r.positionIterations);
    if (!draw.Write(out, width, title)) {
        std::fprintf(stderr, "cannot write %s\n", out.c_str());
        return 1;
    }
    std::printf("wrote %s (%s)\n", out.c_str(), title);
    return 0;
}
