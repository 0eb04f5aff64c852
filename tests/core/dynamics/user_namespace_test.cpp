// A game that writes `using namespace lockbox;`, as the README does, keeps its own names: here
// the game defines kPi, Min, Max, Abs, Round, Sqrt, Clamp, Sin and Cos at global scope, and
// they must compile and mean the game's versions next to the manual's b2 names. This file
// only compiles while lockbox keeps such generic helpers out of namespace lockbox itself (they
// are in lockbox::math).
#include <cmath>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"

// The game's own helpers, deliberately on double and int rather than Fixed.
constexpr double kPi = 3.14159265358979;
constexpr int Min(int a, int b) { return a < b ? a : b; }
constexpr int Max(int a, int b) { return a < b ? b : a; }
constexpr double Abs(double v) { return v < 0 ? -v : v; }
constexpr long Round(double v) { return static_cast<long>(v < 0 ? v - 0.5 : v + 0.5); }
double Sqrt(double v) { return std::sqrt(v); }
constexpr int Clamp(int v, int lo, int hi) { return Max(lo, Min(v, hi)); }
double Sin(double a) { return std::sin(a); }
double Cos(double a) { return std::cos(a); }

using namespace lockbox;

TEST(UserNamespace, GameNamesStayTheGames) {
    EXPECT_EQ(kPi, 3.14159265358979);
    EXPECT_EQ(Min(3, -4), -4);
    EXPECT_EQ(Max(3, -4), 3);
    EXPECT_EQ(Abs(-2.5), 2.5);
    EXPECT_EQ(Round(2.5), 3);
    EXPECT_EQ(Sqrt(16.0), 4.0);
    EXPECT_EQ(Clamp(9, 0, 5), 5);
    EXPECT_EQ(Sin(0.0), 0.0);
    EXPECT_EQ(Cos(0.0), 1.0);
    EXPECT_EQ(Round(kPi * 100), 314);
}

TEST(UserNamespace, ManualNamesSitBesideThem) {
    // The manual's names for the same helpers, on lockbox's numbers.
    EXPECT_EQ(b2_pi.Raw(), 205887);
    EXPECT_EQ(b2Min(Fixed(3), Fixed(-4)), Fixed(-4));
    EXPECT_EQ(b2Max(Fixed(3), Fixed(-4)), Fixed(3));
    EXPECT_EQ(b2Abs(Fixed(-2.5)), Fixed(2.5));
    EXPECT_EQ(b2Sqrt(Fixed(16)), Fixed(4));
    EXPECT_EQ(b2Clamp(Fixed(9), Fixed(0), Fixed(5)), Fixed(5));
    EXPECT_EQ(b2Atan2(Fixed(0), Fixed(1)), Fixed(0));
    // The generic helpers are still reachable, qualified.
    EXPECT_EQ(math::kPi, b2_pi);
    EXPECT_EQ(math::Round(Fixed(2.5)), Fixed(3));
}

TEST(UserNamespace, ManualSnippetsCompileAsWritten) {
    b2World world(b2Vec2(0.0f, -10.0f));
    b2BodyDef bodyDef;
    bodyDef.type = b2_dynamicBody;
    b2Body* bodyA = world.CreateBody(&bodyDef);
    bodyDef.position.Set(1.0f, 0.0f);
    b2Body* bodyB = world.CreateBody(&bodyDef);

    b2RevoluteJointDef jointDef;
    jointDef.Initialize(bodyA, bodyB, bodyA->GetWorldCenter());
    jointDef.lowerAngle = -0.5f * b2_pi;  // -90 degrees
    jointDef.upperAngle = 0.25f * b2_pi;  // 45 degrees
    jointDef.enableLimit = true;
    EXPECT_EQ(jointDef.lowerAngle, Fixed(-0.5f) * b2_pi);
    EXPECT_EQ(jointDef.upperAngle, Fixed(0.25f) * b2_pi);

    const Fixed myLength = 2;
    b2GearJointDef gearDef;
    gearDef.ratio = 2.0f * b2_pi / myLength;
    EXPECT_EQ(gearDef.ratio, Fixed(2.0f) * b2_pi / myLength);

    const b2Vec2 normal(0.0f, -1.0f);
    EXPECT_TRUE(normal.y < -0.5f);
    const b2Vec2 vA(0.0f, 1.0f), vB(0.0f, -2.0f);
    const Fixed approachVelocity = b2Dot(vB - vA, normal);
    EXPECT_TRUE(approachVelocity > 1.0f);
    const Fixed restitution = b2Max(Fixed(0.25f), Fixed(0.5f));
    EXPECT_EQ(restitution, Fixed(0.5f));
}
