// Time of impact (Box2D 2.2.1's b2TimeOfImpact.cpp): conservative advancement with separating
// axes and a secant/bisection root finder, on Q16.16 time fractions.
//
// Why the call always terminates (each loop has a hard cap, and every step inside is finite):
// - b2Distance runs at most b2_maxGjkIterations (20) iterations.
// - The root finder runs at most b2_maxTOIRootIterations (50) iterations. In Q16.16 it can run
//   out of new times before that: its bracket [a1, a2] holds raw integers, every candidate t is
//   clamped strictly inside it (a1 < t < a2), so each iteration shrinks the bracket by at least
//   one raw unit and every bisection step halves it. Starting from at most 65536 raw units
//   (tMax <= 1), the bracket is down to adjacent raw values after at most 17 bisection steps
//   (34 iterations), and the finder stops ("collapsed"). That happens only when the separation
//   changes by more than 2 * tolerance = 164 raw within one raw time unit, i.e. a relative
//   speed above 164 m per unit t (2.2.1's float time would still resolve it): a shape over
//   ~104 m turning at b2_maxRotation per step. The call then returns e_touching at t1 (when
//   a1 == t1) or continues from t2 = a1 > t1. The secant denominator s2 - s1 is never 0:
//   s1 >= target + tolerance and s2 <= target - tolerance hold throughout, so
//   |s2 - s1| >= 164 raw.
// - The push-back loop runs at most b2_maxPolygonVertices (8) times.
// - The outer loop runs at most b2_maxTOIIterations (20) times.
// Hence at most 20 * (1 distance call + 8 * (3 + 50) separation evaluations) per call.

#include "lockbox/collision/TimeOfImpact.h"

namespace lockbox {

namespace {

using detail::gjk::ScaleDirection;
using detail::gjk::TransformPoint;

// Half-width of the accepted band around the target separation: 0.25 * linearSlop
// (m, raw 82 exactly, as 2.2.1's 0.25f * b2_linearSlop = 1.25 mm).
constexpr Fixed kTolerance = Fixed::FromRaw(b2_linearSlop.Raw() / 4);
static_assert(kTolerance.Raw() == 82);

// The separation of two shapes along an axis fixed in one of them (or between two points),
// as a function of the time fraction t.
class SeparationFunction {
public:
    enum Type { e_points, e_faceA, e_faceB };

    // Sets the axis from the GJK cache (1 or 2 vertices) at time t1; returns the separation.
    Fixed Initialize(const b2SimplexCache* cache, const b2DistanceProxy* proxyA, const b2Sweep& sweepA,
                     const b2DistanceProxy* proxyB, const b2Sweep& sweepB, Fixed t1) {
        m_proxyA = proxyA;
        m_proxyB = proxyB;
        m_sweepA = sweepA;
        m_sweepB = sweepB;
        b2Transform xfA, xfB;
        m_sweepA.GetTransform(&xfA, t1);
        m_sweepB.GetTransform(&xfB, t1);

        if (cache->count == 1) {
            m_type = e_points;
            const b2Vec2 pointA = TransformPoint(xfA, proxyA->GetVertex(cache->indexA[0]));
            const b2Vec2 pointB = TransformPoint(xfB, proxyB->GetVertex(cache->indexB[0]));
            m_axis = pointB - pointA;
            return m_axis.Normalize();
        }
        if (cache->indexA[0] == cache->indexA[1]) {
            // Two points on B and one on A: the axis is the normal of B's edge.
            m_type = e_faceB;
            const b2Vec2 b1 = proxyB->GetVertex(cache->indexB[0]);
            const b2Vec2 b2 = proxyB->GetVertex(cache->indexB[1]);
            m_axis = b2Cross(b2 - b1, Fixed(1));
            m_axis.Normalize();
            const b2Vec2 normal = b2Mul(xfB.q, m_axis);
            m_localPoint = b1 + detail::gjk::HalfOf(b2 - b1);
            const b2Vec2 pointB = TransformPoint(xfB, m_localPoint);
            const b2Vec2 pointA = TransformPoint(xfA, proxyA->GetVertex(cache->indexA[0]));
            return OrientAxis(b2Dot(pointA - pointB, normal));
        }
        // Two points on A and one or two on B: the axis is the normal of A's edge.
        m_type = e_faceA;
        const b2Vec2 a1 = proxyA->GetVertex(cache->indexA[0]);
        const b2Vec2 a2 = proxyA->GetVertex(cache->indexA[1]);
        m_axis = b2Cross(a2 - a1, Fixed(1));
        m_axis.Normalize();
        const b2Vec2 normal = b2Mul(xfA.q, m_axis);
        m_localPoint = a1 + detail::gjk::HalfOf(a2 - a1);
        const b2Vec2 pointA = TransformPoint(xfA, m_localPoint);
        const b2Vec2 pointB = TransformPoint(xfB, proxyB->GetVertex(cache->indexB[0]));
        return OrientAxis(b2Dot(pointB - pointA, normal));
    }

    // The deepest pair of features along the axis at time t, and its separation.
    Fixed FindMinSeparation(int32* indexA, int32* indexB, Fixed t) const {
        b2Transform xfA, xfB;
        m_sweepA.GetTransform(&xfA, t);
        m_sweepB.GetTransform(&xfB, t);
        const b2Vec2 dir = ScaleDirection(m_axis);
        switch (m_type) {
            case e_points:
                *indexA = m_proxyA->GetSupport(b2MulT(xfA.q, dir));
                *indexB = m_proxyB->GetSupport(b2MulT(xfB.q, -dir));
                break;
            case e_faceA: {
                const b2Vec2 normal = b2Mul(xfA.q, dir);
                *indexA = -1;
                *indexB = m_proxyB->GetSupport(b2MulT(xfB.q, -normal));
                break;
            }
            case e_faceB: {
                const b2Vec2 normal = b2Mul(xfB.q, dir);
                *indexB = -1;
                *indexA = m_proxyA->GetSupport(b2MulT(xfA.q, -normal));
                break;
            }
        }
        return Separation(*indexA, *indexB, xfA, xfB);
    }

    // The separation of a given pair of features at time t.
    Fixed Evaluate(int32 indexA, int32 indexB, Fixed t) const {
        b2Transform xfA, xfB;
        m_sweepA.GetTransform(&xfA, t);
        m_sweepB.GetTransform(&xfB, t);
        return Separation(indexA, indexB, xfA, xfB);
    }

private:
    Fixed OrientAxis(Fixed s) {
        if (s < Fixed()) {
            m_axis = -m_axis;
            return -s;
        }
        return s;
    }

    Fixed Separation(int32 indexA, int32 indexB, const b2Transform& xfA, const b2Transform& xfB) const {
        switch (m_type) {
            case e_points: {
                const b2Vec2 pointA = TransformPoint(xfA, m_proxyA->GetVertex(indexA));
                const b2Vec2 pointB = TransformPoint(xfB, m_proxyB->GetVertex(indexB));
                return b2Dot(pointB - pointA, m_axis);
            }
            case e_faceA: {
                const b2Vec2 normal = b2Mul(xfA.q, m_axis);
                const b2Vec2 pointA = TransformPoint(xfA, m_localPoint);
                const b2Vec2 pointB = TransformPoint(xfB, m_proxyB->GetVertex(indexB));
                return b2Dot(pointB - pointA, normal);
            }
            case e_faceB: {
                const b2Vec2 normal = b2Mul(xfB.q, m_axis);
                const b2Vec2 pointB = TransformPoint(xfB, m_localPoint);
                const b2Vec2 pointA = TransformPoint(xfA, m_proxyA->GetVertex(indexA));
                return b2Dot(pointA - pointB, normal);
            }
        }
        return Fixed();
    }

    const b2DistanceProxy* m_proxyA = nullptr;
    const b2DistanceProxy* m_proxyB = nullptr;
    b2Sweep m_sweepA, m_sweepB;
    Type m_type = e_points;
    b2Vec2 m_localPoint;  // middle of the reference edge (e_faceA / e_faceB), local frame
    b2Vec2 m_axis;        // unit axis: world (e_points) or local to the face's shape
};

// Next root-finder time strictly inside (a1, a2), which must be at least 2 raw units apart.
// Odd iterations use the secant through (a1, s1) and (a2, s2), even ones bisect.
Fixed NextTime(int32 rootIter, Fixed a1, Fixed a2, Fixed s1, Fixed s2, Fixed target) {
    const int64_t lo = a1.Raw(), hi = a2.Raw();
    int64_t t = 0;
    if (rootIter & 1) {
        // a1 + (target - s1) (a2 - a1) / (s2 - s1): numerator < 2^33 * 2^16, one rounding.
        const int64_t num = (int64_t{target.Raw()} - s1.Raw()) * (hi - lo);
        const int64_t den = int64_t{s2.Raw()} - s1.Raw();
        t = lo + Fixed::DivRaw(num, den, "TOI secant", num);
    } else {
        t = (lo + hi) / 2;  // both non-negative: floor
    }
    if (t <= lo) t = lo + 1;
    if (t >= hi) t = hi - 1;
    return Fixed::FromRaw(static_cast<int32_t>(t));
}

}  // namespace

void b2TimeOfImpact(b2TOIOutput* output, const b2TOIInput* input) {
    output->state = b2TOIOutput::e_unknown;
    output->t = input->tMax;
    output->iterations = 0;
    output->rootIterations = 0;

    const b2DistanceProxy* proxyA = &input->proxyA;
    const b2DistanceProxy* proxyB = &input->proxyB;

    // Large angles make the root finder fail: work on normalised copies.
    b2Sweep sweepA = input->sweepA;
    b2Sweep sweepB = input->sweepB;
    sweepA.Normalize();
    sweepB.Normalize();

    const Fixed tMax = input->tMax;
    const Fixed totalRadius = proxyA->m_radius + proxyB->m_radius;
    const Fixed target = b2Max(b2_linearSlop, totalRadius - Fixed(3) * b2_linearSlop);
    const Fixed tolerance = kTolerance;

    Fixed t1;
    int32 iter = 0;

    b2SimplexCache cache;
    b2DistanceInput distanceInput;
    distanceInput.proxyA = input->proxyA;
    distanceInput.proxyB = input->proxyB;
    distanceInput.useRadii = false;

    // Outer loop: a new separating axis per iteration.
    for (;;) {
        b2Transform xfA, xfB;
        sweepA.GetTransform(&xfA, t1);
        sweepB.GetTransform(&xfB, t1);

        distanceInput.transformA = xfA;
        distanceInput.transformB = xfB;
        b2DistanceOutput distanceOutput;
        b2Distance(&distanceOutput, &cache, &distanceInput);

        // The core shapes overlap: give up on continuous collision.
        if (distanceOutput.distance <= Fixed()) {
            output->state = b2TOIOutput::e_overlapped;
            output->t = Fixed();
            break;
        }
        if (distanceOutput.distance < target + tolerance) {
            output->state = b2TOIOutput::e_touching;
            output->t = t1;
            break;
        }

        SeparationFunction fcn;
        fcn.Initialize(&cache, proxyA, sweepA, proxyB, sweepB, t1);

        // Resolve the deepest point on this axis, at most one push-back per vertex.
        bool done = false;
        Fixed t2 = tMax;
        int32 pushBackIter = 0;
        for (;;) {
            int32 indexA = 0, indexB = 0;
            Fixed s2 = fcn.FindMinSeparation(&indexA, &indexB, t2);

            if (s2 > target + tolerance) {
                // Separated at the end of the interval.
                if (t2 == tMax) {
                    output->state = b2TOIOutput::e_separated;
                    output->t = tMax;
                    done = true;
                    break;
                }
                // Separated at an earlier t2 (rounding of a converged root, or the safe side of a
                // collapsed bracket): 2.2.1 would report e_separated at tMax here and could let
                // the shapes pass; advance to t2 instead and let the outer loop look again.
                t1 = t2;
                break;
            }
            // Within tolerance at t2: advance the sweeps.
            if (s2 > target - tolerance) {
                t1 = t2;
                break;
            }

            Fixed s1 = fcn.Evaluate(indexA, indexB, t1);
            // Already too close at t1 (the root finder may have run out of iterations).
            if (s1 < target - tolerance) {
                output->state = b2TOIOutput::e_failed;
                output->t = t1;
                done = true;
                break;
            }
            // Touching at t1 (possibly t1 = 0).
            if (s1 <= target + tolerance) {
                output->state = b2TOIOutput::e_touching;
                output->t = t1;
                done = true;
                break;
            }

            // Root of s(t) = target in [t1, t2], bracketed by s1 > target > s2.
            int32 rootIterCount = 0;
            Fixed a1 = t1, a2 = t2;
            bool collapsed = false;
            while (rootIterCount < b2_maxTOIRootIterations) {
                if (a2.Raw() - a1.Raw() <= 1) {
                    collapsed = true;
                    break;
                }
                const Fixed t = NextTime(rootIterCount, a1, a2, s1, s2, target);
                const Fixed s = fcn.Evaluate(indexA, indexB, t);
                ++rootIterCount;
                if (b2Abs(s - target) < tolerance) {
                    t2 = t;  // tentative new t1
                    break;
                }
                // Keep the root bracketed.
                if (s > target) {
                    a1 = t;
                    s1 = s;
                } else {
                    a2 = t;
                    s2 = s;
                }
            }
            output->rootIterations += rootIterCount;
            if (collapsed) {
                // The separation crosses the whole band target +- tolerance within one raw time
                // unit: Q16.16 cannot resolve the root. a1 is the last raw time at which this
                // pair is still beyond the band.
                if (a1 == t1) {
                    // Everything is separated at t1 (the distance test above) and the deepest
                    // pair is too close one raw unit later: t1 is the time of impact.
                    output->state = b2TOIOutput::e_touching;
                    output->t = t1;
                    done = true;
                    break;
                }
                t2 = a1;  // safe for this pair: look for deeper pairs there
            }

            ++pushBackIter;
            if (pushBackIter == b2_maxPolygonVertices) break;
        }

        ++iter;
        output->iterations = iter;
        if (done) break;
        if (iter == b2_maxTOIIterations) {
            // The root finder got stuck: t1 is still a safe time.
            output->state = b2TOIOutput::e_failed;
            output->t = t1;
            break;
        }
    }
}

}  // namespace lockbox
