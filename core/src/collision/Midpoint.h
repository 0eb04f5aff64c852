#pragma once
// The midpoint of two body-frame points as the polygon and the circle manifolds place a contact
// point or clip plane: one rounding of the exact sum. (The world manifold rounds on the
// difference instead, so that its midpoint moves exactly with a translation: Manifold.cpp.)

#include <cstdint>

#include "lockbox/fixed/Vec2.h"

namespace lockbox::collision_detail {

/// round((a + b) / 2) per axis: the exact sum, rounded once (ties away from zero).
inline b2Vec2 MidpointRoundedOnSum(const b2Vec2& a, const b2Vec2& b) {
    const int64_t sx = int64_t{a.x.Raw()} + b.x.Raw();
    const int64_t sy = int64_t{a.y.Raw()} + b.y.Raw();
    return {Fixed::FromRaw(detail::NarrowRaw(detail::ShiftRound(sx, 1), "MidpointRoundedOnSum", sx, 0)),
            Fixed::FromRaw(detail::NarrowRaw(detail::ShiftRound(sy, 1), "MidpointRoundedOnSum", sy, 0))};
}

}  // namespace lockbox::collision_detail
