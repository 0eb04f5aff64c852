// Polygon validation (b2ValidatePolygon) and the convex hull behind SetFromHull. Every test is
// exact integer arithmetic on raw coordinates; the only tolerances are b2_polygonWeldDistance
// and b2_minPolygonArea (Shape.h explains both).

#include <vector>

#include "ShapeInternal.h"
#include "lockbox/collision/PolygonShape.h"

namespace lockbox {

using shape_detail::Cross3Raw;
using shape_detail::DistanceSquaredRaw;

namespace {

constexpr int64_t kWeld = b2_polygonWeldDistance.Raw();
constexpr int64_t kWeldSquared = kWeld * kWeld;  // Q32.32 raw, 26896

// True when `p` lies closer than the weld distance to the line through a and b (a != b):
// cross(b - a, p - a)^2 < weld^2 * |b - a|^2, in 128 bits (cross < 2^61, |b - a|^2 < 2^61).
bool NearLine(const b2Vec2& a, const b2Vec2& b, const b2Vec2& p) noexcept {
    const int64_t cross = Cross3Raw(a, b, p);
    return shape_detail::CompareProducts(cross, cross, kWeldSquared, DistanceSquaredRaw(a, b)) < 0;
}

}  // namespace

b2ShapeError b2ValidatePolygon(const b2Vec2* points, int32 count) noexcept {
    if (count < 3) return b2ShapeError::tooFewVertices;
    if (count > b2_maxPolygonVertices) return b2ShapeError::tooManyVertices;
    for (int32 i = 0; i < count; ++i) {
        if (!shape_detail::InShapeRange(points[i])) return b2ShapeError::outOfRange;
    }
    for (int32 i = 0; i < count; ++i) {
        for (int32 j = i + 1; j < count; ++j) {
            if (DistanceSquaredRaw(points[i], points[j]) < kWeldSquared) return b2ShapeError::duplicateVertices;
        }
    }
    // Collinear: every point near the line of one edge (the whole set is a sliver), or a
    // vertex near the chord of its two neighbours (a redundant vertex).
    for (int32 i = 0; i < count; ++i) {
        const b2Vec2& a = points[i];
        const b2Vec2& b = points[i + 1 < count ? i + 1 : 0];
        bool allNear = true;
        for (int32 j = 0; j < count && allNear; ++j) allNear = NearLine(a, b, points[j]);
        if (allNear) return b2ShapeError::collinear;
    }
    for (int32 i = 0; i < count; ++i) {
        const b2Vec2& prev = points[i > 0 ? i - 1 : count - 1];
        const b2Vec2& next = points[i + 1 < count ? i + 1 : 0];
        if (NearLine(prev, next, points[i])) return b2ShapeError::collinear;
    }
    // Strict convexity: every other vertex strictly left of each edge (counter-clockwise) or
    // strictly right of each (clockwise). Exact, so no b2_epsilon is needed.
    bool allLeft = true, allRight = true;
    for (int32 i = 0; i < count; ++i) {
        const int32 i2 = i + 1 < count ? i + 1 : 0;
        for (int32 j = 0; j < count; ++j) {
            if (j == i || j == i2) continue;
            const int64_t s = Cross3Raw(points[i], points[i2], points[j]);
            allLeft = allLeft && s > 0;
            allRight = allRight && s < 0;
        }
    }
    if (!allLeft) return allRight ? b2ShapeError::clockwise : b2ShapeError::notConvex;
    // Twice the area as a Q32.32 raw: the fan sum is exact (each term < 2^61, at most 6 terms
    // of one sign for a convex polygon).
    int64_t twiceArea = 0;
    for (int32 i = 1; i + 1 < count; ++i) twiceArea += Cross3Raw(points[0], points[i], points[i + 1]);
    if (twiceArea < 2 * b2_minPolygonArea.Raw()) return b2ShapeError::areaTooSmall;
    return b2ShapeError::ok;
}

b2ShapeError b2PolygonShape::SetFromHull(const b2Vec2* points, int32 count) {
    if (count < 3) return b2ShapeError::tooFewVertices;
    for (int32 i = 0; i < count; ++i) {
        if (!shape_detail::InShapeRange(points[i])) return b2ShapeError::outOfRange;
    }
    // Gift wrapping from the lowest-x point (ties: lowest y), which is always a hull vertex.
    // Each step keeps the candidate with every other point on its left; among exactly
    // collinear candidates the farther one wins, so hull edges carry no interior points. With
    // exact predicates the result depends only on the coordinates, never on input order.
    int32 start = 0;
    for (int32 i = 1; i < count; ++i) {
        const b2Vec2& p = points[i];
        const b2Vec2& s = points[start];
        if (p.x < s.x || (p.x == s.x && p.y < s.y)) start = i;
    }
    std::vector<b2Vec2> hull;
    b2Vec2 current = points[start];
    for (int32 guard = 0; guard <= count; ++guard) {
        hull.push_back(current);
        int32 best = -1;
        for (int32 j = 0; j < count; ++j) {
            if (points[j] == current) continue;
            if (best < 0) {
                best = j;
                continue;
            }
            const int64_t s = Cross3Raw(current, points[best], points[j]);
            if (s < 0 ||
                (s == 0 && DistanceSquaredRaw(current, points[j]) > DistanceSquaredRaw(current, points[best]))) {
                best = j;
            }
        }
        if (best < 0) break;  // every point equals `current`
        current = points[best];
        if (current == hull.front()) break;
    }
    // Weld: drop the first vertex (in hull order, which is data-defined) that is closer than
    // the weld distance to its successor or to its neighbours' chord, and repeat. Each drop
    // moves the boundary inwards by less than the weld distance.
    bool changed = true;
    while (changed && hull.size() >= 3) {
        changed = false;
        const size_t n = hull.size();
        for (size_t i = 0; i < n && !changed; ++i) {
            const b2Vec2& prev = hull[(i + n - 1) % n];
            const b2Vec2& next = hull[(i + 1) % n];
            if (DistanceSquaredRaw(hull[i], next) < kWeldSquared || NearLine(prev, next, hull[i])) {
                hull.erase(hull.begin() + static_cast<std::ptrdiff_t>(i));
                changed = true;
            }
        }
    }
    if (hull.size() < 3) return b2ShapeError::collinear;
    if (hull.size() > static_cast<size_t>(b2_maxPolygonVertices)) return b2ShapeError::tooManyVertices;
    return Set(hull.data(), static_cast<int32>(hull.size()));
}

}  // namespace lockbox
