#pragma once
// Private helpers of the shape implementations: exact 128-bit comparisons and products of raw
// fixed-point values. Not installed; only core/src/collision/shapes/*.cpp include it.

#include <cstdint>

#include "lockbox/collision/Shape.h"
#include "lockbox/fixed/detail/Int128.h"

namespace lockbox::shape_detail {

using detail::S128;
using detail::U128;

/// An int64 as S128.
constexpr S128 ToS128(int64_t v) noexcept { return detail::MulS64(v, 1); }

/// Sign of a - b as -1, 0 or +1. Both magnitudes must stay below 2^127.
constexpr int Compare(const S128& a, const S128& b) noexcept {
    const S128 d = detail::SubS128(a, b);
    if (detail::IsZero(d)) return 0;
    return d.negative ? -1 : 1;
}

/// Sign of a*b - c*d for int64 operands, exactly.
constexpr int CompareProducts(int64_t a, int64_t b, int64_t c, int64_t d) noexcept {
    return Compare(detail::MulS64(a, b), detail::MulS64(c, d));
}

/// Number of significant bits of |v| (0 for 0).
constexpr int BitWidth(const S128& v) noexcept { return detail::BitWidthU128(v.mag); }

/// round(a * b / 2^shift) narrowed to a Q32.32 raw, saturating (and reporting) when the true
/// result leaves the int64 range. Exact even when a*b would not fit 128 bits: in that case
/// |a*b| >= 2^126, so the shifted result (shift <= 62) overflows int64 anyway.
constexpr int64_t MulShiftNarrow(const S128& a, int64_t b, int shift, const char* op) noexcept {
    const int width = BitWidth(a) + BitWidth(ToS128(b));
    if (width > 127) {
        S128 huge;
        huge.negative = a.negative != (b < 0);
        huge.mag = U128{~uint64_t{0} >> 1, 0};
        return detail::NarrowWide(huge, op, b, shift);
    }
    return detail::NarrowWide(detail::ShrRoundS128(detail::MulS128S64(a, b), shift), op, b, shift);
}

/// floor(sqrt(n)) for any 128-bit n (the result fits 64 bits).
constexpr uint64_t IsqrtFloor128(U128 n) noexcept {
    if (n.hi == 0) return detail::IsqrtFloor64(n.lo);
    uint64_t root = 0;
    for (int bit = 63; bit >= 0; --bit) {
        const uint64_t candidate = root | (uint64_t{1} << bit);
        if (!detail::LessU128(n, detail::MulU64(candidate, candidate))) root = candidate;
    }
    return root;
}

/// |v| <= limit for a raw coordinate.
constexpr bool InRange(Fixed v, Fixed limit) noexcept { return v.Raw() <= limit.Raw() && v.Raw() >= -limit.Raw(); }

/// Both coordinates within b2_maxShapeCoordinate.
constexpr bool InShapeRange(const b2Vec2& v) noexcept {
    return InRange(v.x, b2_maxShapeCoordinate) && InRange(v.y, b2_maxShapeCoordinate);
}

/// b2_chainWeldDistance squared as a Q32.32 raw, the bound DistanceSquaredRaw is held to: edge
/// and chain vertices closer than this are rejected as duplicates by both shapes alike.
constexpr int64_t kChainWeldSquared = int64_t{b2_chainWeldDistance.Raw()} * b2_chainWeldDistance.Raw();

/// Exact squared distance of two points as a Q32.32 raw (coordinates within the shape range,
/// so each difference is below 2^30 raw and the sum below 2^61).
constexpr int64_t DistanceSquaredRaw(const b2Vec2& a, const b2Vec2& b) noexcept {
    const int64_t dx = int64_t{a.x.Raw()} - b.x.Raw();
    const int64_t dy = int64_t{a.y.Raw()} - b.y.Raw();
    return dx * dx + dy * dy;
}

/// Exact cross((b - a), (c - a)) as a Q32.32 raw for points within the shape range (|result|
/// < 2^61).
constexpr int64_t Cross3Raw(const b2Vec2& a, const b2Vec2& b, const b2Vec2& c) noexcept {
    const int64_t ex = int64_t{b.x.Raw()} - a.x.Raw(), ey = int64_t{b.y.Raw()} - a.y.Raw();
    const int64_t fx = int64_t{c.x.Raw()} - a.x.Raw(), fy = int64_t{c.y.Raw()} - a.y.Raw();
    return ex * fy - ey * fx;
}

/// The AABB of a segment, fattened by radius.
b2AABB SegmentAABB(const b2Vec2& v1, const b2Vec2& v2, Fixed radius) noexcept;

/// Ray cast against the segment v1-v2 given in the frame xf (shared by edges and chains).
bool RayCastSegment(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& xf, const b2Vec2& v1,
                    const b2Vec2& v2);

/// Area centroid of a validated polygon (exact sums, one rounding per coordinate).
b2Vec2 ComputePolygonCentroid(const b2Vec2* vertices, int32 count) noexcept;

}  // namespace lockbox::shape_detail
