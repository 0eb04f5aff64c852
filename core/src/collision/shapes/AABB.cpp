// b2AABB::RayCast: the slab method of 2.2.1 with every slab fraction kept as an exact ratio.

#include "ShapeInternal.h"
#include "lockbox/collision/Collision.h"

namespace lockbox {

namespace {
// A fraction num / den with den > 0.
struct Ratio {
    int64_t num;
    int64_t den;
};
// a < b, exactly (|num| < 2^34, den < 2^33: the products fit 128 bits trivially).
bool Less(const Ratio& a, const Ratio& b) noexcept {
    return shape_detail::CompareProducts(a.num, b.den, b.num, a.den) < 0;
}
}  // namespace

bool b2AABB::RayCast(b2RayCastOutput* output, const b2RayCastInput& input) const {
    // 2.2.1 starts with tmin = -maxFloat, tmax = +maxFloat; here "unset" flags stand in.
    Ratio tmin{0, 1}, tmax{0, 1};
    bool hasMin = false, hasMax = false;
    b2Vec2 normal;
    for (int i = 0; i < 2; ++i) {
        const int64_t p = input.p1(i).Raw();
        const int64_t d = int64_t{input.p2(i).Raw()} - p;
        const int64_t lower = lowerBound(i).Raw(), upper = upperBound(i).Raw();
        if (d == 0) {
            // Parallel to this slab (2.2.1: |d| < epsilon; a zero raw is the exact test).
            if (p < lower || upper < p) return false;
            continue;
        }
        // Entry and exit fractions with a positive denominator; s is the entry normal's sign.
        const bool negative = d < 0;
        const int64_t den = negative ? -d : d;
        Ratio t1{negative ? p - upper : lower - p, den};
        Ratio t2{negative ? p - lower : upper - p, den};
        const Fixed s = negative ? Fixed(1) : Fixed(-1);
        if (!hasMin || Less(tmin, t1)) {
            normal.SetZero();
            normal(i) = s;
            tmin = t1;
            hasMin = true;
        }
        if (!hasMax || Less(t2, tmax)) {
            tmax = t2;
            hasMax = true;
        }
        if (Less(tmax, tmin)) return false;
    }
    // A ray parallel to both axes has zero length: 2.2.1's tmin stays -maxFloat and it misses.
    if (!hasMin) return false;
    // Starting inside (tmin < 0) or ending before the box (tmin > maxFraction): no hit.
    if (tmin.num < 0) return false;
    if (shape_detail::CompareProducts(tmin.num, Fixed::kOneRaw, input.maxFraction.Raw(), tmin.den) > 0) return false;
    output->fraction = Fixed::FromRatio(tmin.num, tmin.den);
    output->normal = normal;
    return true;
}

}  // namespace lockbox
