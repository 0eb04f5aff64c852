// Test 2: free fall and projectile against the symplectic-Euler closed form, a box on a slope
// (slides iff tan(theta) > mu, acceleration g (sin - mu cos)), bounce heights for restitution.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "DynamicsTestUtil.h"
#include "FixedPrint.h"

namespace lockbox::test {
namespace LOCKBOX_TEST_FILE {

// Symplectic Euler with exact arithmetic: v_n = v0 + n h g, p_n = p0 + h sum_{k=1..n} v_k.
double ClosedFormPosition(double p0, double v0, double g, double h, int n) {
    return p0 + n * h * v0 + h * h * g * n * (n + 1) / 2.0;
}

TEST(Motion, FreeFallMatchesSymplecticEuler) {
    b2World world(b2Vec2(0, -10));
    b2Body* body = MakeDynamicCircle(world, 0, 100, Fixed(0.5));
    const double h = kDtDouble;
    for (int n = 1; n <= 120; ++n) {
        world.Step(kDt, 8, 3);
        const double y = body->GetPosition().y.ToDouble();
        const double vy = body->GetLinearVelocity().y.ToDouble();
        // h*g rounds to exactly -10920 raw, so v_n is exact; each position update adds one
        // rounding of at most half an ULP.
        EXPECT_NEAR(vy, -10.0 * h * n, 1e-9) << "step " << n;
        EXPECT_NEAR(y, ClosedFormPosition(100, 0, -10, h, n), n * 0.5 / 65536 + 1e-9) << "step " << n;
    }
    EXPECT_EQ(body->GetPosition().x, Fixed());
}

TEST(Motion, ProjectileMatchesSymplecticEuler) {
    b2World world(b2Vec2(0, -10));
    b2Body* body = MakeDynamicCircle(world, -50, 10, Fixed(0.25));
    body->SetLinearVelocity(b2Vec2(12, 15));
    const double h = kDtDouble;
    for (int n = 1; n <= 150; ++n) {
        world.Step(kDt, 8, 3);
        const b2Vec2 p = body->GetPosition();
        EXPECT_NEAR(p.x.ToDouble(), ClosedFormPosition(-50, 12, 0, h, n), n * 0.5 / 65536 + 1e-9) << n;
        EXPECT_NEAR(p.y.ToDouble(), ClosedFormPosition(10, 15, -10, h, n), n * 0.5 / 65536 + 1e-9) << n;
    }
}

struct SlopeResult {
    double accel;   // measured along the slope, m/s^2
    double travel;  // distance travelled in the measuring window, m
};

// A 1 m box resting on a wide static slope at angle theta with friction mu on both fixtures
// (sqrt mixing gives mu exactly). Returns the acceleration along the slope from steps 60..180.
SlopeResult RunSlope(Fixed theta, Fixed mu) {
    b2World world(b2Vec2(0, -10));
    b2Rot q(theta);
    // Ground surface through the origin: the slab's centre lies 1 m below along the normal.
    const b2Vec2 normal(-q.s, q.c);
    MakeStaticBox(world, -normal.x, -normal.y, 40, 1, theta, mu);
    // Box centre 0.5 m above the surface (plus the two polygon skins).
    const Fixed up = Fixed(0.5) + Fixed(0.02);
    b2Body* box = MakeDynamicBox(world, up * normal.x, up * normal.y, Fixed(0.5), Fixed(0.5), 1, mu, 0, theta);
    box->SetSleepingAllowed(false);
    const b2Vec2 down(q.c, q.s);  // unit vector along the slope
    double s0 = 0, v0 = 0;
    for (int n = 1; n <= 180; ++n) {
        world.Step(kDt, 8, 3);
        if (n == 60) {
            s0 = b2Dot(box->GetPosition(), down).ToDouble();
            v0 = b2Dot(box->GetLinearVelocity(), down).ToDouble();
        }
    }
    const double s1 = b2Dot(box->GetPosition(), down).ToDouble();
    const double v1 = b2Dot(box->GetLinearVelocity(), down).ToDouble();
    const double t = 120 * kDtDouble;
    return {(v1 - v0) / t, s1 - s0};
}

TEST(Motion, BoxOnSlopeSlidesOnlyWhenTanExceedsMu) {
    // 30 degrees: tan = 0.577.
    const Fixed theta = Fixed(0.5235987756);
    const double th = theta.ToDouble();
    // mu = 0.7 > tan: it sticks (less than a millimetre in two seconds).
    const SlopeResult stick = RunSlope(theta, Fixed(0.7));
    EXPECT_LT(std::fabs(stick.travel), 1e-3);
    std::printf("slope mu 0.70: travel %.6f m\n", stick.travel);
    // mu = 0.2 and 0.4 < tan: it slides with a = g (sin - mu cos) within 2 %.
    for (const Fixed mu : {Fixed(0.2), Fixed(0.4)}) {
        const SlopeResult slide = RunSlope(theta, mu);
        // The slope points down toward -x here: "down" is +x rotated, so a < 0 along it.
        const double expected = -10.0 * (std::sin(th) - mu.ToDouble() * std::cos(th));
        EXPECT_NEAR(slide.accel, expected, 0.02 * std::fabs(expected)) << "mu " << mu.ToDouble();
        std::printf("slope mu %.2f: a = %.5f expected %.5f\n", mu.ToDouble(), slide.accel, expected);
    }
}

// Drops a circle from 5 m onto the ground; returns the apex of the first bounce (m above the
// resting height).
double BounceHeight(Fixed restitution) {
    b2World world(b2Vec2(0, -10));
    MakeStaticBox(world, 0, -1, 20, 1, 0, Fixed(0.2), restitution);
    const Fixed r = Fixed(0.5);
    b2Body* ball = MakeDynamicCircle(world, 0, Fixed(5) + r, r, 1, Fixed(0.2), restitution);
    bool bounced = false;
    double apex = 0;
    for (int n = 0; n < 600; ++n) {
        world.Step(kDt, 8, 3);
        const double vy = ball->GetLinearVelocity().y.ToDouble();
        const double y = ball->GetPosition().y.ToDouble() - r.ToDouble();
        if (!bounced && vy > 0) bounced = true;
        if (bounced) {
            apex = std::max(apex, y);
            if (vy < 0) break;
        }
    }
    return apex;
}

TEST(Motion, BounceHeightFollowsRestitutionSquared) {
    const double h0 = 5.0;
    std::printf("bounce heights: e=0 %.4f, e=0.5 %.4f, e=1 %.4f\n", BounceHeight(Fixed()), BounceHeight(Fixed(0.5)),
                BounceHeight(Fixed(1)));
    // e = 0: no bounce at all (a few millimetres of position correction at most).
    EXPECT_LT(BounceHeight(Fixed()), 0.01);
    // e = 0.5: h = e^2 h0 = 1.25 m within 5 %.
    EXPECT_NEAR(BounceHeight(Fixed(0.5)), 0.25 * h0, 0.05 * 0.25 * h0);
    // e = 1: back to the drop height within 5 %.
    EXPECT_NEAR(BounceHeight(Fixed(1)), h0, 0.05 * h0);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::test
