// World state hash (b2WorldHash): identical worlds agree, a one-raw-ULP change is caught and
// narrowed to the right category and body, listeners and debug draw are not state, and long
// runs repeat.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

const Fixed kDt = Fixed::FromRatio(1, 60);

/// A small world with every category populated: ground, a box stack, a circle, a pendulum
/// on a revolute joint. Returns the world; ids are deterministic.
std::unique_ptr<b2World> MakeWorld() {
    auto world = std::make_unique<b2World>(b2Vec2(0, -10));
    b2BodyDef groundDef;
    b2Body* ground = world->CreateBody(&groundDef);
    b2PolygonShape groundBox;
    groundBox.SetAsBox(40, 1);
    ground->CreateFixture(&groundBox, 0);

    b2PolygonShape box;
    box.SetAsBox(0.5_fx, 0.5_fx);
    for (int i = 0; i < 5; ++i) {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position = b2Vec2(Fixed(0), Fixed(2) + Fixed(i) * 1.05_fx);
        b2Body* b = world->CreateBody(&def);
        b2FixtureDef fd;
        fd.shape = &box;
        fd.density = 1;
        fd.friction = 0.6_fx;
        b->CreateFixture(&fd);
    }
    b2CircleShape circle;
    circle.m_radius = 0.4_fx;
    b2BodyDef ballDef;
    ballDef.type = b2_dynamicBody;
    ballDef.position = b2Vec2(Fixed(3), Fixed(6));
    ballDef.angularVelocity = 2;
    world->CreateBody(&ballDef)->CreateFixture(&circle, 2);

    b2BodyDef armDef;
    armDef.type = b2_dynamicBody;
    armDef.position = b2Vec2(Fixed(-6), Fixed(8));
    b2Body* arm = world->CreateBody(&armDef);
    b2PolygonShape armBox;
    armBox.SetAsBox(1, 0.2_fx);
    arm->CreateFixture(&armBox, 1);
    b2RevoluteJointDef jd;
    jd.Initialize(ground, arm, b2Vec2(Fixed(-7), Fixed(8)));
    world->CreateJoint(&jd);
    return world;
}

void StepN(b2World& world, int steps) {
    for (int i = 0; i < steps; ++i) world.Step(kDt, 8, 3);
}

TEST(StateHash, IdenticalWorldsAgree) {
    auto a = MakeWorld();
    auto b = MakeWorld();
    EXPECT_EQ(b2WorldHash(*a), b2WorldHash(*b));
    StepN(*a, 90);
    StepN(*b, 90);
    const b2WorldHashReport ra = b2WorldHashDetailed(*a);
    const b2WorldHashReport rb = b2WorldHashDetailed(*b);
    EXPECT_EQ(ra.total, b2WorldHash(*a));
    EXPECT_EQ(ra.total, rb.total);
    ASSERT_EQ(ra.bodies.size(), rb.bodies.size());
    EXPECT_EQ(ra.bodies.size(), static_cast<size_t>(a->GetBodyCount()));
    const b2HashMismatch m = b2CompareHashReports(ra, rb);
    EXPECT_EQ(m.category, b2HashCategory::e_count);
    EXPECT_EQ(m.bodyId, -1);
    // Contacts and joints exist, so those categories are exercised.
    EXPECT_GT(a->GetContactCount(), 0);
    EXPECT_EQ(a->GetJointCount(), 1);
}

TEST(StateHash, HashChangesWhileSimulating) {
    auto a = MakeWorld();
    const uint64 h0 = b2WorldHash(*a);
    StepN(*a, 1);
    EXPECT_NE(h0, b2WorldHash(*a));
}

TEST(StateHash, OneUlpPositionChangeIsNarrowedToTheBody) {
    auto a = MakeWorld();
    auto b = MakeWorld();
    StepN(*a, 30);
    StepN(*b, 30);
    // The third body created (second box): same call on both worlds, one raw ULP apart in x,
    // so the only difference is that ULP.
    b2Body* ba = a->GetBody(2);
    b2Body* bb = b->GetBody(2);
    ASSERT_NE(ba, nullptr);
    ASSERT_NE(bb, nullptr);
    const b2Vec2 p = ba->GetPosition();
    ba->SetTransform(p, ba->GetAngle());
    bb->SetTransform(b2Vec2(Fixed::FromRaw(p.x.Raw() + 1), p.y), bb->GetAngle());

    const b2WorldHashReport ra = b2WorldHashDetailed(*a);
    const b2WorldHashReport rb = b2WorldHashDetailed(*b);
    EXPECT_NE(ra.total, rb.total);
    const b2HashMismatch m = b2CompareHashReports(ra, rb);
    EXPECT_EQ(m.category, b2HashCategory::e_bodies) << b2HashCategoryName(m.category);
    EXPECT_EQ(m.bodyId, 2);
    EXPECT_EQ(ra.categories[static_cast<int>(b2HashCategory::e_settings)],
              rb.categories[static_cast<int>(b2HashCategory::e_settings)]);
    EXPECT_EQ(ra.categories[static_cast<int>(b2HashCategory::e_joints)],
              rb.categories[static_cast<int>(b2HashCategory::e_joints)]);
    int differing = 0;
    for (size_t i = 0; i < ra.bodies.size(); ++i) differing += ra.bodies[i].hash != rb.bodies[i].hash;
    EXPECT_EQ(differing, 1);
}

TEST(StateHash, EachCategoryReactsToItsOwnState) {
    auto a = MakeWorld();
    auto b = MakeWorld();
    b->SetWarmStarting(false);
    EXPECT_EQ(b2CompareHashReports(b2WorldHashDetailed(*a), b2WorldHashDetailed(*b)).category,
              b2HashCategory::e_settings);
    b->SetWarmStarting(true);
    b->GetFixture(0)->SetFriction(0.25_fx);
    const b2HashMismatch m = b2CompareHashReports(b2WorldHashDetailed(*a), b2WorldHashDetailed(*b));
    EXPECT_EQ(m.category, b2HashCategory::e_fixtures);
    EXPECT_EQ(m.bodyId, 0);  // the per-body hash includes the body's fixtures
}

class CountingListener : public b2ContactListener {
public:
    void BeginContact(b2Contact*) override { ++begins; }
    int begins = 0;
};

class NullDraw : public b2Draw {
public:
    void DrawPolygon(const b2Vec2*, int32, const b2Color&) override { ++calls; }
    void DrawSolidPolygon(const b2Vec2*, int32, const b2Color&) override { ++calls; }
    void DrawCircle(const b2Vec2&, Fixed, const b2Color&) override { ++calls; }
    void DrawSolidCircle(const b2Vec2&, Fixed, const b2Vec2&, const b2Color&) override { ++calls; }
    void DrawSegment(const b2Vec2&, const b2Vec2&, const b2Color&) override { ++calls; }
    void DrawTransform(const b2Transform&) override { ++calls; }
    int calls = 0;
};

TEST(StateHash, ListenersAndDebugDrawAreNotState) {
    auto plain = MakeWorld();
    auto observed = MakeWorld();
    CountingListener listener;
    NullDraw draw;
    draw.SetFlags(b2Draw::e_shapeBit | b2Draw::e_jointBit | b2Draw::e_aabbBit | b2Draw::e_pairBit |
                  b2Draw::e_centerOfMassBit);
    observed->SetContactListener(&listener);
    observed->SetDebugDraw(&draw);
    for (int i = 0; i < 120; ++i) {
        plain->Step(kDt, 8, 3);
        observed->Step(kDt, 8, 3);
        observed->DrawDebugData();
        ASSERT_EQ(b2WorldHash(*plain), b2WorldHash(*observed)) << "step " << i;
    }
    EXPECT_GT(listener.begins, 0);
    EXPECT_GT(draw.calls, 0);
}

TEST(StateHash, StableAcrossTwoRunsOf600Steps) {
    std::vector<uint64> first;
    for (int run = 0; run < 2; ++run) {
        auto w = MakeWorld();
        for (int i = 0; i < 600; ++i) {
            w->Step(kDt, 8, 3);
            const uint64 h = b2WorldHash(*w);
            if (run == 0) {
                first.push_back(h);
            } else {
                ASSERT_EQ(h, first[static_cast<size_t>(i)]) << "step " << i;
            }
        }
    }
}

TEST(StateHash, BodyFieldsNameTheWalksRecord) {
    // b2BodyStateFields reads a body through the hash's own walk: every field it writes has a
    // name, and a one-raw change of a body's state shows in exactly the field that moved.
    auto a = MakeWorld();
    auto b = MakeWorld();
    for (int i = 0; i < 30; ++i) {
        a->Step(kDt, 8, 3);
        b->Step(kDt, 8, 3);
    }
    b2Body* moved = b->GetBodyList();
    while (moved != nullptr && moved->GetType() != b2_dynamicBody) moved = moved->GetNext();
    ASSERT_NE(moved, nullptr);
    moved->SetAwake(true);  // so the change below moves the velocity alone
    // Setting a velocity drops the part below Q16.16 that the solver left: drop it first, so
    // that the one-raw change below moves a single field.
    moved->SetAngularVelocity(moved->GetAngularVelocity());
    const std::vector<b2BodyField> before = b2BodyStateFields(*moved);
    ASSERT_EQ(before.size(), 40u);
    for (const b2BodyField& f : before) EXPECT_STRNE(f.name, "field");
    moved->SetAngularVelocity(moved->GetAngularVelocity() + Fixed::FromRaw(1));
    const std::vector<b2BodyField> after = b2BodyStateFields(*moved);
    ASSERT_EQ(after.size(), before.size());
    int changed = 0;
    for (size_t i = 0; i < after.size(); ++i) {
        if (after[i].raw == before[i].raw) continue;
        ++changed;
        EXPECT_STREQ(after[i].name, "angularVelocity");
        EXPECT_EQ(after[i].format, b2FieldFormat::e_fixed);
    }
    EXPECT_EQ(changed, 1);
}

TEST(StateHash, CategoryNames) {
    EXPECT_EQ(b2HashCategoryName(b2HashCategory::e_broadphase), "broadphase");
    EXPECT_EQ(b2HashCategoryName(b2HashCategory::e_count), "none");
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
