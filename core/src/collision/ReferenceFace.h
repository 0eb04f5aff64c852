#pragma once
// The hysteresis of the reference-face choice, one rule for the polygon-polygon and the
// edge-polygon manifolds (Box2D 2.2.1 repeats its k_relativeTol and k_absoluteTol in both).

#include <cstdint>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Wide.h"

namespace lockbox::collision_detail {

/// Box2D's k_relativeTol = 0.98 and k_absoluteTol = 0.001 m: face B is chosen only when sepB >
/// 0.98 * sepA + 0.001 m. The relative factor is kept as the exact ratio 98/100; the absolute
/// one is 0.001 m rounded to raw 66 (1.007 mm, about linearSlop / 5), as in Box2D a small
/// fraction of the slop so that nearly equal separations keep the previous face and the contact
/// ids stay stable.
inline constexpr int64_t k_relativeTolNum = 98;
inline constexpr int64_t k_relativeTolDen = 100;
inline constexpr Fixed k_absoluteTol = Fixed::FromRaw(66);

/// True when separationB > k_relativeTol * separationA + k_absoluteTol, compared exactly:
/// 100 * sepB > 98 * sepA + 100 * tol in Q32.32 raw. Separations are dot products of in-range
/// differences with unit normals, so |sep| < 2^16 m (2^48 raw) and the scaled sums stay below
/// 2^55: no overflow.
inline bool PreferSecond(Wide separationA, Wide separationB) {
    const int64_t lhs = k_relativeTolDen * separationB.Raw();
    const int64_t rhs = k_relativeTolNum * separationA.Raw() + k_relativeTolDen * Wide(k_absoluteTol).Raw();
    return lhs > rhs;
}

}  // namespace lockbox::collision_detail
