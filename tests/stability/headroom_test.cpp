// Headroom telemetry (lockbox/state/Headroom.h): the walk, its limits, the profile switch and
// the saturation count.

#include "lockbox/state/Headroom.h"

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox;
using C = b2HeadroomClass;

b2Body* AddBox(b2World& w, const b2Vec2& p, Fixed half, Fixed density) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position = p;
    b2Body* b = w.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(half, half);
    b->CreateFixture(&box, density);
    return b;
}

TEST(Headroom, LimitsAreTheFormats) {
    const b2Headroom h;
    EXPECT_EQ(h[C::e_position].limit, static_cast<uint64>(Fixed::kMaxRaw));
    EXPECT_EQ(h[C::e_velocity].limit, static_cast<uint64>(Fixed::kMaxRaw));
    EXPECT_EQ(h[C::e_impulse].limit, static_cast<uint64>(Wide::kMaxRaw));
    EXPECT_EQ(h[C::e_invInertia].limit, static_cast<uint64>(Wide::kMaxRaw));
    EXPECT_EQ(h[C::e_treeCost].limit, static_cast<uint64>(Wide::kMaxRaw));
    EXPECT_EQ(h.saturations, 0);
    for (int i = 0; i < static_cast<int>(C::e_count); ++i) EXPECT_STRNE(b2HeadroomClassName(static_cast<C>(i)), "none");
}

TEST(Headroom, WalkRecordsExactMagnitudes) {
    b2World world(b2Vec2(0, -10));
    b2Body* b = AddBox(world, b2Vec2(100, -200), 1, 2);  // 2 m box, density 2: 8 kg
    b->SetLinearVelocity(b2Vec2(-3, 1));
    b->SetAngularVelocity(-5);
    const b2Headroom h = b2MeasureHeadroom(world);
    EXPECT_EQ(h[C::e_position].maxRaw, 200u * 65536u);
    EXPECT_EQ(h[C::e_velocity].maxRaw, 3u * 65536u);
    EXPECT_EQ(h[C::e_angularVelocity].maxRaw, 5u * 65536u);
    EXPECT_EQ(h[C::e_mass].maxRaw, static_cast<uint64>(b->GetMass().Raw()));
    EXPECT_EQ(h[C::e_mass].maxRaw, 8ull << 32);
    // The box is centred on its origin: its central inertia is GetInertia(), and its inverse
    // mass is the one division the body makes.
    EXPECT_EQ(h[C::e_invMass].maxRaw, static_cast<uint64>((Wide(1) / b->GetMass()).Raw()));
    EXPECT_EQ(h[C::e_inertia].maxRaw, static_cast<uint64>(b->GetInertia().Raw()));
    // The fat AABB reaches past the body by the skin and aabbExtension.
    EXPECT_GT(h[C::e_treeBounds].maxRaw, 201u * 65536u);
    EXPECT_GT(h[C::e_treeCost].maxRaw, 0u);
    EXPECT_EQ(h[C::e_impulse].maxRaw, 0u);
    // The fat AABB reaches furthest: 200 m plus the skin and aabbExtension, of 32768 m.
    EXPECT_EQ(h.Tightest(), C::e_treeBounds);
    // 200 * 2^16 * 1e6 / (2^31 - 1) = 6103.52: rounded to nearest.
    EXPECT_EQ(h[C::e_position].PartsPerMillion(), 6104);
    // Large Q32.32 magnitudes must not overflow the product (1e6 * 2^62 needs 128 bits).
    b2HeadroomEntry big{uint64{1} << 62, static_cast<uint64>(Wide::kMaxRaw)};
    EXPECT_EQ(big.PartsPerMillion(), 500000);
}

TEST(Headroom, ProfileIsFilledOnlyWhenEnabled) {
    b2World world(b2Vec2(0, -10));
    b2BodyDef gd;
    b2Body* ground = world.CreateBody(&gd);
    b2PolygonShape g;
    g.SetAsBox(10, 1);
    ground->CreateFixture(&g, 0);
    AddBox(world, b2Vec2(0, Fixed(1.5)), Fixed(0.5), 1);
    EXPECT_FALSE(world.GetHeadroomTelemetry());
    for (int i = 0; i < 30; ++i) world.Step(Fixed::FromRaw(1092), 8, 3);
    EXPECT_EQ(world.GetProfile().headroom[C::e_position].maxRaw, 0u);
    world.SetHeadroomTelemetry(true);
    world.Step(Fixed::FromRaw(1092), 8, 3);
    const b2Headroom& h = world.GetProfile().headroom;
    EXPECT_GT(h[C::e_position].maxRaw, 0u);
    // The box rests on the ground: its contact carries an impulse.
    EXPECT_GT(h[C::e_impulse].maxRaw, 0u);
    EXPECT_EQ(h.saturations, 0);
    // The walk matches a direct measurement after the step.
    const b2Headroom direct = b2MeasureHeadroom(world);
    for (int i = 0; i < static_cast<int>(C::e_count); ++i) EXPECT_EQ(h.entries[i].maxRaw, direct.entries[i].maxRaw);
}

TEST(Headroom, MergeKeepsMaximaAndAddsSaturations) {
    b2Headroom a, b;
    a[C::e_velocity].maxRaw = 5;
    b[C::e_velocity].maxRaw = 7;
    b[C::e_mass].maxRaw = 3;
    a.saturations = 2;
    b.saturations = 1;
    a.Merge(b);
    EXPECT_EQ(a[C::e_velocity].maxRaw, 7u);
    EXPECT_EQ(a[C::e_mass].maxRaw, 3u);
    EXPECT_EQ(a.saturations, 3);
}

TEST(Headroom, StepCountsSaturations) {
    if (kOverflowTraps) GTEST_SKIP() << "checked builds trap instead of saturating";
    b2World world(b2Vec2(0, 0));
    world.SetHeadroomTelemetry(true);
    // A 0.1 m box at density 0.1 (1e-3 kg) pushed by 30000 N, 1 m from the edge of the Q16.16
    // range: dv = F/m dt = 5e5 m/s per step fits the Q32.32 velocity, the step's motion is then
    // clamped to b2_maxTranslation (2 m), and that carries the centre past 32767 m: integrating
    // the position saturates.
    b2Body* b = AddBox(world, b2Vec2(32766, 0), Fixed(0.05), Fixed(0.1));
    b->ApplyForceToCenter(b2Vec2(30000, 0));
    world.Step(Fixed::FromRaw(1092), 8, 3);
    EXPECT_GT(world.GetProfile().headroom.saturations, 0);
    EXPECT_EQ(static_cast<int64_t>(world.GetSaturationCount()), world.GetProfile().headroom.saturations);
}

}  // namespace LOCKBOX_TEST_FILE
