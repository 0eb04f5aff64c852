// Shape overlap test (Box2D 2.2.1's b2TestOverlap in b2Collision.cpp): GJK with radii.

#include "lockbox/collision/Collision.h"
#include "lockbox/collision/Distance.h"

namespace lockbox {

namespace {
// 2.2.1 reports overlap when the rounded-shape distance is below 10 * FLT_EPSILON = 1.2e-6 m,
// i.e. a distance that is zero up to float noise. That is 0.08 of a Q16.16 unit; the smallest
// non-zero Fixed distance is 1 raw (1.5e-5 m), so the same test is "distance < 1 raw": the
// shapes overlap or touch (b2Distance with radii returns exactly 0 in both cases).
constexpr int32 kOverlapDistanceRaw = 1;
}  // namespace

bool b2TestOverlap(const b2Shape* shapeA, int32 indexA, const b2Shape* shapeB, int32 indexB, const b2Transform& xfA,
                   const b2Transform& xfB) {
    b2DistanceInput input;
    input.proxyA.Set(shapeA, indexA);
    input.proxyB.Set(shapeB, indexB);
    input.transformA = xfA;
    input.transformB = xfB;
    input.useRadii = true;

    b2SimplexCache cache;
    b2DistanceOutput output;
    b2Distance(&output, &cache, &input);
    return output.distance.Raw() < kOverlapDistanceRaw;
}

}  // namespace lockbox
