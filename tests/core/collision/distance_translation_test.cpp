// Translation invariance: the same configuration moved by whole metres, up to +-15,000 m,
// gives bit-identical GJK and TOI results (witness points moved by exactly the translation).
//
// Why it holds: world points are formed as p + round(R v) (the rounding never sees the
// translation), every later quantity is a difference of two world points, and the witness
// points are the first simplex vertex plus a rounded offset. Whole metres are exact in Q16.16.

#include <array>
#include <random>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/TimeOfImpact.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

struct Cloud {
    std::array<b2Vec2, 8> v;
    int32 count = 0;
    Fixed radius;
};

class TranslationRng {
public:
    explicit TranslationRng(uint64_t seed) : engine_(seed) {}
    int32_t Raw(int32_t lo, int32_t hi) {
        return static_cast<int32_t>(lo + static_cast<int64_t>(engine_() % static_cast<uint64_t>(int64_t{hi} - lo + 1)));
    }
    Fixed Metres(int lo, int hi) { return Fixed::FromRaw(Raw(lo * 65536, hi * 65536)); }

private:
    std::mt19937_64 engine_;
};

Cloud RandomCloud(TranslationRng& rng) {
    Cloud c;
    const int kind = rng.Raw(0, 2);
    if (kind == 0) {  // circle
        c.count = 1;
        c.v[0] = b2Vec2(Fixed::FromRaw(rng.Raw(-20000, 20000)), Fixed::FromRaw(rng.Raw(-20000, 20000)));
        c.radius = Fixed::FromRaw(rng.Raw(5000, 80000));
    } else if (kind == 1) {  // segment
        c.count = 2;
        c.v[0] = b2Vec2(rng.Metres(-1, 1), rng.Metres(-1, 1));
        c.v[1] = c.v[0] + b2Vec2(rng.Metres(-2, 2), rng.Metres(-2, 2));
        c.radius = b2_polygonRadius;
    } else {  // convex polygon on an ellipse
        c.count = rng.Raw(3, 8);
        const Fixed rx = Fixed::FromRaw(rng.Raw(8000, 90000)), ry = Fixed::FromRaw(rng.Raw(8000, 90000));
        const int32_t sector = 411775 / c.count;
        for (int32 i = 0; i < c.count; ++i) {
            const b2Rot dir(Fixed::FromRaw(i * sector + rng.Raw(-sector / 4, sector / 4)));
            c.v[static_cast<size_t>(i)] = b2Vec2(rx * dir.c, ry * dir.s);
        }
        c.radius = b2_polygonRadius;
    }
    return c;
}

b2DistanceProxy ProxyOf(const Cloud& c) {
    b2DistanceProxy p;
    p.Set(c.v.data(), c.count, c.radius);
    return p;
}

TEST(DistanceTranslation, GjkIsBitIdenticalUnderWholeMetreShifts) {
    TranslationRng rng(20261122);
    const b2Vec2 shifts[] = {{15000, 15000}, {-15000, -15000}, {15000, -15000}, {-15000, 7}, {1, -1}, {-9999, 12345}};
    for (int pair = 0; pair < 400; ++pair) {
        const Cloud a = RandomCloud(rng), b = RandomCloud(rng);
        b2DistanceInput in;
        in.proxyA = ProxyOf(a);
        in.proxyB = ProxyOf(b);
        // Straddle the origin so that the shifts change the sign of coordinates.
        in.transformA.Set(b2Vec2(rng.Metres(-2, 2), rng.Metres(-2, 2)), Fixed::FromRaw(rng.Raw(-205887, 205887)));
        in.transformB.Set(in.transformA.p + b2Vec2(rng.Metres(-3, 3), rng.Metres(-3, 3)),
                          Fixed::FromRaw(rng.Raw(-205887, 205887)));
        in.useRadii = (pair & 1) != 0;
        b2SimplexCache baseCache;
        b2DistanceOutput base;
        b2Distance(&base, &baseCache, &in);
        for (const b2Vec2& shift : shifts) {
            b2DistanceInput moved = in;
            moved.transformA.p += shift;
            moved.transformB.p += shift;
            b2SimplexCache cache;
            b2DistanceOutput out;
            b2Distance(&out, &cache, &moved);
            ASSERT_EQ(out.distance, base.distance) << pair;
            ASSERT_EQ(out.iterations, base.iterations) << pair;
            ASSERT_EQ(out.pointA - shift, base.pointA) << pair;
            ASSERT_EQ(out.pointB - shift, base.pointB) << pair;
            ASSERT_EQ(cache.count, baseCache.count) << pair;
            ASSERT_EQ(cache.metric, baseCache.metric) << pair;
            for (int i = 0; i < cache.count; ++i) {
                ASSERT_EQ(cache.indexA[i], baseCache.indexA[i]) << pair;
                ASSERT_EQ(cache.indexB[i], baseCache.indexB[i]) << pair;
            }
        }
    }
}

TEST(DistanceTranslation, ToiIsBitIdenticalUnderWholeMetreShifts) {
    TranslationRng rng(4242);
    const b2Vec2 shifts[] = {{15000, 15000}, {-15000, -15000}, {-15000, 15000}, {3, -2}};
    for (int pair = 0; pair < 300; ++pair) {
        const Cloud a = RandomCloud(rng), b = RandomCloud(rng);
        b2TOIInput in;
        in.proxyA = ProxyOf(a);
        in.proxyB = ProxyOf(b);
        for (b2Sweep* s : {&in.sweepA, &in.sweepB}) {
            s->localCenter = b2Vec2(Fixed::FromRaw(rng.Raw(-10000, 10000)), Fixed::FromRaw(rng.Raw(-10000, 10000)));
            s->c0 = b2Vec2(rng.Metres(-3, 3), rng.Metres(-3, 3));
            s->c = b2Vec2(rng.Metres(-3, 3), rng.Metres(-3, 3));
            s->a0 = Fixed::FromRaw(rng.Raw(-205887, 205887));
            s->a = s->a0 + Fixed::FromRaw(rng.Raw(-98304, 98304));
        }
        in.tMax = Fixed(1);
        b2TOIOutput base;
        b2TimeOfImpact(&base, &in);
        for (const b2Vec2& shift : shifts) {
            b2TOIInput moved = in;
            for (b2Sweep* s : {&moved.sweepA, &moved.sweepB}) {
                s->c0 += shift;
                s->c += shift;
            }
            b2TOIOutput out;
            b2TimeOfImpact(&out, &moved);
            ASSERT_EQ(out.state, base.state) << pair;
            ASSERT_EQ(out.t, base.t) << pair;
            ASSERT_EQ(out.iterations, base.iterations) << pair;
            ASSERT_EQ(out.rootIterations, base.rootIterations) << pair;
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
