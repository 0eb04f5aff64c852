// b2TimeOfImpact against closed-form impact times, a fast bullet against a thin wall,
// separated and overlapping cases, rotating sweeps and the iteration caps.

#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/TimeOfImpact.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

std::array<b2Vec2, 4> ToiBox(Fixed hx, Fixed hy) {
    return {b2Vec2(-hx, -hy), b2Vec2(hx, -hy), b2Vec2(hx, hy), b2Vec2(-hx, hy)};
}

b2Sweep Linear(b2Vec2 from, b2Vec2 to, Fixed a0 = Fixed(), Fixed a = Fixed()) {
    b2Sweep s;
    s.c0 = from;
    s.c = to;
    s.a0 = a0;
    s.a = a;
    return s;
}

b2TOIOutput Toi(const b2DistanceProxy& a, const b2Sweep& sa, const b2DistanceProxy& b, const b2Sweep& sb,
                Fixed tMax = Fixed(1)) {
    b2TOIInput in;
    in.proxyA = a;
    in.proxyB = b;
    in.sweepA = sa;
    in.sweepB = sb;
    in.tMax = tMax;
    b2TOIOutput out;
    b2TimeOfImpact(&out, &in);
    return out;
}

// Core distance of the two shapes at time t of their sweeps.
Fixed CoreDistanceAt(const b2DistanceProxy& a, const b2Sweep& sa, const b2DistanceProxy& b, const b2Sweep& sb,
                     Fixed t) {
    b2DistanceInput in;
    in.proxyA = a;
    in.proxyB = b;
    sa.GetTransform(&in.transformA, t);
    sb.GetTransform(&in.transformB, t);
    b2SimplexCache cache;
    b2DistanceOutput out;
    b2Distance(&out, &cache, &in);
    return out.distance;
}

constexpr double kSlop = 328.0 / 65536.0;
constexpr double kTolerance = 82.0 / 65536.0;

TEST(ToiAnalytic, BoxesApproachingHeadOn) {
    const auto box = ToiBox(0.5_fx, 0.5_fx);
    b2DistanceProxy a, b;
    a.Set(box.data(), 4, b2_polygonRadius);
    b.Set(box.data(), 4, b2_polygonRadius);
    // A rests at the origin, B comes from x = 5 to x = -3: the core gap is 4 - 8t.
    const b2TOIOutput out = Toi(a, Linear({0, 0}, {0, 0}), b, Linear({5, 0}, {-3, 0}));
    ASSERT_EQ(out.state, b2TOIOutput::e_touching);
    const double target = std::max(kSlop, 2 * 656.0 / 65536.0 - 3 * kSlop);
    const double expected = (4.0 - target) / 8.0;
    EXPECT_NEAR(out.t.ToDouble(), expected, kTolerance / 8.0 + 2.0 / 65536.0);
    // Both moving, towards each other at 3 and 5 m per step, at an angle: gap 4 - 8t again.
    const b2TOIOutput both = Toi(a, Linear({-1, 2}, {2, 2}), b, Linear({4, 2.25_fx}, {-1, 2.25_fx}));
    ASSERT_EQ(both.state, b2TOIOutput::e_touching);
    EXPECT_NEAR(both.t.ToDouble(), expected, kTolerance / 8.0 + 2.0 / 65536.0);
    EXPECT_GE(both.iterations, 1);
}

TEST(ToiAnalytic, CirclesAtKnownSpeed) {
    const b2Vec2 origin;
    b2DistanceProxy a, b;
    a.Set(&origin, 1, 0.5_fx);
    b.Set(&origin, 1, 0.25_fx);
    // Centres 10 m apart closing at 12 m per step; target = 0.75 - 3 slop.
    const b2TOIOutput out = Toi(a, Linear({0, 0}, {2, 0}), b, Linear({10, 0}, {0, 0}));
    ASSERT_EQ(out.state, b2TOIOutput::e_touching);
    const double target = 0.75 - 3 * kSlop;
    EXPECT_NEAR(out.t.ToDouble(), (10.0 - target) / 12.0, kTolerance / 12.0 + 2.0 / 65536.0);
}

TEST(ToiAnalytic, BulletNeverTunnelsThroughThinWall) {
    const auto wall = ToiBox(0.05_fx, 3);
    const auto bullet = ToiBox(0.05_fx, 0.05_fx);
    b2DistanceProxy w, b;
    w.Set(wall.data(), 4, b2_polygonRadius);
    b.Set(bullet.data(), 4, b2_polygonRadius);
    const double target = std::max(kSlop, 2 * 656.0 / 65536.0 - 3 * kSlop);
    int touching = 0;
    for (int i = 0; i < 200; ++i) {
        // Start 2..22 m to the left, end 2..22 m to the right, various heights and spins.
        const Fixed x0 = -Fixed(2) - Fixed::FromRaw(i * 6553);
        const Fixed x1 = Fixed(2) + Fixed::FromRaw((199 - i) * 6553);
        const Fixed y0 = Fixed::FromRaw((i * 7919) % 262144 - 131072);
        const Fixed y1 = Fixed::FromRaw((i * 104729) % 262144 - 131072);
        const b2Sweep bulletSweep = Linear({x0, y0}, {x1, y1}, Fixed(), Fixed::FromRaw((i % 13 - 6) * 20000));
        const b2Sweep wallSweep = Linear({0, 0}, {0, 0});
        const b2TOIOutput out = Toi(w, wallSweep, b, bulletSweep);
        ASSERT_EQ(out.state, b2TOIOutput::e_touching) << i;
        ++touching;
        // At the time of impact the bullet is still on the near side, in the target band.
        const Fixed d = CoreDistanceAt(w, wallSweep, b, bulletSweep, out.t);
        EXPECT_GT(d.ToDouble(), target - kTolerance - 1e-5) << i;
        EXPECT_LT(d.ToDouble(), target + kTolerance + 1e-5) << i;
        b2Transform xf;
        bulletSweep.GetTransform(&xf, out.t);
        EXPECT_LT(xf.p.x.ToDouble(), 0.0) << i;
    }
    EXPECT_EQ(touching, 200);
}

TEST(ToiAnalytic, SeparatedReturnsTMax) {
    const auto box = ToiBox(0.5_fx, 0.5_fx);
    b2DistanceProxy a, b;
    a.Set(box.data(), 4, b2_polygonRadius);
    b.Set(box.data(), 4, b2_polygonRadius);
    // Parallel motion 2 m apart.
    const b2TOIOutput par = Toi(a, Linear({0, 0}, {5, 0}), b, Linear({0, 2}, {5, 2}));
    EXPECT_EQ(par.state, b2TOIOutput::e_separated);
    EXPECT_EQ(par.t, Fixed(1));
    // Approaching, but the interval ends before contact: t = tMax.
    const b2TOIOutput early = Toi(a, Linear({0, 0}, {0, 0}), b, Linear({5, 0}, {-3, 0}), 0.25_fx);
    EXPECT_EQ(early.state, b2TOIOutput::e_separated);
    EXPECT_EQ(early.t, 0.25_fx);
    // Moving apart.
    const b2TOIOutput away = Toi(a, Linear({0, 0}, {-1, 0}), b, Linear({1.5_fx, 0}, {4, 1}));
    EXPECT_EQ(away.state, b2TOIOutput::e_separated);
    EXPECT_EQ(away.t, Fixed(1));
}

TEST(ToiAnalytic, OverlappedAndTouchingAtStart) {
    const auto box = ToiBox(0.5_fx, 0.5_fx);
    b2DistanceProxy a, b;
    a.Set(box.data(), 4, b2_polygonRadius);
    b.Set(box.data(), 4, b2_polygonRadius);
    const b2TOIOutput over = Toi(a, Linear({0, 0}, {0, 0}), b, Linear({0.5_fx, 0.25_fx}, {3, 0}));
    EXPECT_EQ(over.state, b2TOIOutput::e_overlapped);
    EXPECT_EQ(over.t, Fixed());
    // Core gap exactly the target at t = 0: touching immediately.
    const Fixed gap = b2_linearSlop;
    const b2TOIOutput touch = Toi(a, Linear({0, 0}, {0, 0}), b, Linear({Fixed(1) + gap, 0}, {3, 0}));
    EXPECT_EQ(touch.state, b2TOIOutput::e_touching);
    EXPECT_EQ(touch.t, Fixed());
}

TEST(ToiAnalytic, RotatingRodHitsCircle) {
    const auto rod = ToiBox(2, 0.05_fx);
    const b2Vec2 origin;
    b2DistanceProxy a, b;
    a.Set(rod.data(), 4, b2_polygonRadius);
    b.Set(&origin, 1, 0.1_fx);
    // The rod spins a quarter turn about its centre; the circle waits at (0, 1.5). The core
    // distance is 1.5 cos(theta) - 0.05 while the circle's projection stays on the rod.
    const Fixed halfPi = Fixed::FromRaw(102944);
    const b2TOIOutput out = Toi(a, Linear({0, 0}, {0, 0}, Fixed(), halfPi), b, Linear({0, 1.5_fx}, {0, 1.5_fx}));
    ASSERT_EQ(out.state, b2TOIOutput::e_touching);
    const double target = std::max(kSlop, 0.1 + 656.0 / 65536.0 - 3 * kSlop);
    const double theta = std::acos((target + 0.05) / 1.5);
    const double expected = theta / (102944.0 / 65536.0);
    const double slope = 1.5 * std::sin(theta) * (102944.0 / 65536.0);  // d(distance)/dt
    EXPECT_NEAR(out.t.ToDouble(), expected, kTolerance / slope + 1e-4);

    // Rotation and translation together: the rod also slides up by 0.5 m.
    const b2TOIOutput both = Toi(a, Linear({0, 0}, {0, 0.5_fx}, Fixed(), halfPi), b, Linear({0, 1.5_fx}, {0, 1.5_fx}));
    ASSERT_EQ(both.state, b2TOIOutput::e_touching);
    EXPECT_LT(both.t, out.t);
    const Fixed d =
        CoreDistanceAt(a, Linear({0, 0}, {0, 0.5_fx}, Fixed(), halfPi), b, Linear({0, 1.5_fx}, {0, 1.5_fx}), both.t);
    EXPECT_NEAR(d.ToDouble(), target, kTolerance + 1e-5);
}

TEST(ToiAnalytic, LargeAnglesAreNormalised) {
    const auto box = ToiBox(0.5_fx, 0.25_fx);
    b2DistanceProxy a, b;
    a.Set(box.data(), 4, b2_polygonRadius);
    b.Set(box.data(), 4, b2_polygonRadius);
    // The same motion with the angles shifted by 100 turns of the Q16.16 2*pi.
    const Fixed turns = Fixed::FromRaw(100 * 411775);
    const b2TOIOutput base =
        Toi(a, Linear({0, 0}, {0, 0}, 0.2_fx, 1.2_fx), b, Linear({4, 0.1_fx}, {-2, 0}, -0.3_fx, 0.4_fx));
    const b2TOIOutput shifted = Toi(a, Linear({0, 0}, {0, 0}, 0.2_fx + turns, 1.2_fx + turns), b,
                                    Linear({4, 0.1_fx}, {-2, 0}, -0.3_fx - turns, 0.4_fx - turns));
    EXPECT_EQ(base.state, b2TOIOutput::e_touching);
    EXPECT_EQ(base.state, shifted.state);
    EXPECT_EQ(base.t, shifted.t);
}

TEST(ToiAnalytic, ExtremeSpinStopsOnAdjacentRawTimes) {
    // A 4 km rod turning a quarter turn in one sweep sweeps a circle 1414 m from its centre
    // at about 2200 m per unit t, i.e. 34 mm per raw time unit (2^-16): far more than the
    // 2.5 mm band target +- tolerance. The root finder's bracket shrinks to adjacent raw times
    // without meeting the band; the call must still end, at the last safe raw time.
    const auto rod = ToiBox(2000, 0.05_fx);
    const b2Vec2 origin;
    b2DistanceProxy a, b;
    a.Set(rod.data(), 4, b2_polygonRadius);
    b.Set(&origin, 1, 0.5_fx);
    const b2Sweep spin = Linear({0, 0}, {0, 0}, Fixed(), Fixed::FromRaw(102944));
    const b2Sweep still = Linear({1000, 1000}, {1000, 1000});
    const b2TOIOutput out = Toi(a, spin, b, still);
    ASSERT_EQ(out.state, b2TOIOutput::e_touching);
    EXPECT_LE(out.iterations, b2_maxTOIIterations);
    const double target = std::max(kSlop, 0.5 + 656.0 / 65536.0 - 3 * kSlop);
    // Not yet interpenetrating at t, and already too close two raw units later.
    EXPECT_GT(CoreDistanceAt(a, spin, b, still, out.t).ToDouble(), target - kTolerance);
    EXPECT_LT(CoreDistanceAt(a, spin, b, still, out.t + Fixed::FromRaw(2)).ToDouble(), target);
    // The impact is near 45 degrees of the quarter turn.
    EXPECT_NEAR(out.t.ToDouble(), 0.5, 0.01);
}

TEST(ToiAnalytic, IterationCountsStayWithinCaps) {
    const auto box = ToiBox(1, 0.1_fx);
    b2DistanceProxy a, b;
    a.Set(box.data(), 4, b2_polygonRadius);
    b.Set(box.data(), 4, b2_polygonRadius);
    for (int i = 0; i < 100; ++i) {
        const Fixed spin = Fixed::FromRaw(i * 3001 - 150000);
        const b2TOIOutput out = Toi(a, Linear({0, 0}, {Fixed::FromRaw(i * 900), 0}, Fixed(), spin), b,
                                    Linear({3, Fixed::FromRaw(i * 1111 - 50000)}, {-1, 0}, spin, -spin));
        EXPECT_NE(out.state, b2TOIOutput::e_unknown);
        EXPECT_LE(out.iterations, b2_maxTOIIterations);
        EXPECT_LE(out.rootIterations, b2_maxTOIIterations * b2_maxPolygonVertices * b2_maxTOIRootIterations);
        EXPECT_GE(out.t, Fixed());
        EXPECT_LE(out.t, Fixed(1));
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
