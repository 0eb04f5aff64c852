#pragma once
// A polygon made by SetAsBox(hx, hy): centred on its body, edges along its axes, the commonest
// shape of all. Its corners' symmetry gives some results without visiting every corner, with the
// bits of the visit (the AABB, the support corner of the polygon collision).

#include <cstdint>

#include "lockbox/collision/PolygonShape.h"

namespace lockbox::shape_detail {

/// Half-extents (raw Q16.16) small enough that no sum of two products of a corner coordinate and
/// a rotation or unit-vector component (each at most 2^17 raw) leaves 2^48.
struct CentredBox {
    int64_t hx = 0, hy = 0;
};

/// Whether vertices v[0..count) are the corners (-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy) in
/// that order, with 0 < hx, hy < 2^30 raw; if so, their half-extents.
inline bool AsCentredBox(const b2Vec2* v, int32 count, CentredBox* box) noexcept {
    if (count != 4) return false;
    const Fixed hx = v[2].x, hy = v[2].y;
    constexpr int32 kMaxHalf = int32{1} << 30;
    if (hx.Raw() <= 0 || hy.Raw() <= 0 || hx.Raw() >= kMaxHalf || hy.Raw() >= kMaxHalf) return false;
    if (v[0] != b2Vec2(-hx, -hy) || v[1] != b2Vec2(hx, -hy) || v[3] != b2Vec2(-hx, hy)) return false;
    *box = {hx.Raw(), hy.Raw()};
    return true;
}

/// Whether a centred box's normals are the axes SetAsBox gives it: (0, -1), (1, 0), (0, 1),
/// (-1, 0) for edges 0 to 3 (the vertices alone do not say it; the normals are public fields).
inline bool HasAxisNormals(const b2Vec2* n) noexcept {
    constexpr int32 kOne = Fixed::kOneRaw;
    return n[0].x.Raw() == 0 && n[0].y.Raw() == -kOne && n[1].x.Raw() == kOne && n[1].y.Raw() == 0 &&
           n[2].x.Raw() == 0 && n[2].y.Raw() == kOne && n[3].x.Raw() == -kOne && n[3].y.Raw() == 0;
}

/// Whether a rotation or direction component is in the range the shortcuts assume.
constexpr bool InUnitRange(Fixed x) noexcept {
    constexpr int32 kMax = int32{1} << 17;
    return x.Raw() <= kMax && x.Raw() >= -kMax;
}

/// The corner of a centred box with the least exact dot product with n, the first in vertex
/// order on a tie (as a scan keeping the first minimum finds it): the corner whose signs oppose
/// n's. Only a zero component of n ties two corners (hx, hy > 0).
constexpr int32 CentredBoxSupport(const b2Vec2& n) noexcept {
    const int32 x = n.x.Raw(), y = n.y.Raw();
    // Corners: 0 (-, -), 1 (+, -), 2 (+, +), 3 (-, +).
    if (y > 0) return x < 0 ? 1 : 0;  // y pulls to the lower corners; x = 0 ties 0 and 1
    if (y < 0) return x > 0 ? 3 : 2;  // the upper ones; x = 0 ties 2 and 3
    return x < 0 ? 1 : 0;             // y = 0 ties each pair of one side: 0 and 3, or 1 and 2
}

}  // namespace lockbox::shape_detail
