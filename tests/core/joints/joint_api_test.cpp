// Joint lifetime and API: creation, ids, lists, user data, collideConnected, destruction
// listener, the gear joint's dependency rule, and "no joints, no joint loop".
#include <vector>

#include <gtest/gtest.h>

#include "JointTestUtil.h"

namespace lockbox::jt {
namespace LOCKBOX_TEST_FILE {

struct Listener : b2DestructionListener {
    std::vector<b2Joint*> joints;
    void SayGoodbye(b2Joint* j) override { joints.push_back(j); }
    void SayGoodbye(b2Fixture*) override {}
};

TEST(JointApi, CreateListsAndDefaults) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 0, 5, Fixed(0.5), 1);
    b2Body* b = Box(world, 2, 5, Fixed(0.5), 1);

    b2RevoluteJointDef rd;
    rd.Initialize(ground, a, b2Vec2(0, 6));
    rd.userData = 42;
    EXPECT_FALSE(rd.collideConnected);
    b2Joint* r = world.CreateJoint(&rd);
    ASSERT_NE(r, nullptr);
    b2DistanceJointDef dd;
    dd.Initialize(a, b, a->GetPosition(), b->GetPosition());
    b2Joint* d = world.CreateJoint(&dd);
    ASSERT_NE(d, nullptr);

    EXPECT_EQ(world.GetJointCount(), 2);
    EXPECT_EQ(world.GetJointList(), d);  // newest first
    EXPECT_EQ(d->GetNext(), r);
    EXPECT_EQ(r->GetNext(), nullptr);
    EXPECT_EQ(r->GetId(), 0);
    EXPECT_EQ(d->GetId(), 1);
    EXPECT_EQ(r->GetUserData(), 42u);
    EXPECT_EQ(r->GetBodyA(), ground);
    EXPECT_EQ(r->GetBodyB(), a);
    EXPECT_EQ(r->GetType(), e_revoluteJoint);
    EXPECT_FALSE(r->GetCollideConnected());
    EXPECT_EQ(static_cast<b2DistanceJoint*>(d)->GetLength(), Fixed(2));

    // Body joint lists hold both edges.
    int edges = 0;
    for (b2JointEdge* je = a->GetJointList(); je; je = je->next) ++edges;
    EXPECT_EQ(edges, 2);

    // Ids are reused, smallest first.
    world.DestroyJoint(r);
    EXPECT_EQ(world.GetJointCount(), 1);
    b2Joint* r2 = world.CreateJoint(&rd);
    EXPECT_EQ(r2->GetId(), 0);

    // Invalid definitions are refused.
    b2JointDef unknown;
    unknown.bodyA = ground;
    unknown.bodyB = a;
    EXPECT_EQ(world.CreateJoint(&unknown), nullptr);
    b2GearJointDef badGear;
    badGear.joint1 = d;  // a distance joint cannot be geared
    badGear.joint2 = r2;
    EXPECT_EQ(world.CreateJoint(&badGear), nullptr);
}

TEST(JointApi, CollideConnectedFalseStopsContacts) {
    // Two overlapping boxes joined by a revolute: without collideConnected they never touch.
    b2World world(b2Vec2(0, 0));
    b2Body* a = Box(world, 0, 0, Fixed(0.5), 1);
    b2Body* b = Box(world, Fixed(0.5), 0, Fixed(0.5), 1);
    b2RevoluteJointDef rd;
    rd.Initialize(a, b, b2Vec2(Fixed(0.25), 0));
    world.CreateJoint(&rd);
    Step(world, 5);
    int touching = 0;
    for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) touching += c->IsTouching() ? 1 : 0;
    EXPECT_EQ(touching, 0);
}

TEST(JointApi, DestroyBodyDestroysJointsWithGoodbye) {
    b2World world(b2Vec2(0, -10));
    Listener listener;
    world.SetDestructionListener(&listener);
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 0, 5, Fixed(0.5), 1);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, a, b2Vec2(0, 6));
    b2Joint* r = world.CreateJoint(&rd);
    world.DestroyBody(a);
    ASSERT_EQ(listener.joints.size(), 1u);
    EXPECT_EQ(listener.joints[0], r);
    EXPECT_EQ(world.GetJointCount(), 0);
    EXPECT_EQ(ground->GetJointList(), nullptr);
    Step(world, 2);
}

// The gear rule: destroying a joint a gear depends on destroys the gear first, and the
// listener hears of the gear (an implicit destruction).
TEST(JointApi, GearDiesWithItsJoints) {
    for (int which = 0; which < 3; ++which) {
        b2World world(b2Vec2(0, -10));
        Listener listener;
        world.SetDestructionListener(&listener);
        b2Body* ground = Ground(world);
        b2Body* a = Ball(world, 0, 5, 1, 1);
        b2Body* b = Ball(world, 3, 5, 1, 1);
        b2RevoluteJointDef r1;
        r1.Initialize(ground, a, a->GetPosition());
        b2Joint* j1 = world.CreateJoint(&r1);
        b2PrismaticJointDef p2;
        p2.Initialize(ground, b, b->GetPosition(), b2Vec2(0, 1));
        b2Joint* j2 = world.CreateJoint(&p2);
        b2GearJointDef gd;
        gd.joint1 = j1;
        gd.joint2 = j2;
        gd.ratio = 2;
        b2Joint* gear = world.CreateJoint(&gd);
        ASSERT_NE(gear, nullptr);
        EXPECT_EQ(gear->GetBodyA(), a);
        EXPECT_EQ(gear->GetBodyB(), b);
        Step(world, 10);

        if (which == 0) {
            world.DestroyJoint(j1);  // explicit: the gear is implicit
            ASSERT_EQ(listener.joints.size(), 1u);
            EXPECT_EQ(listener.joints[0], gear);
            EXPECT_EQ(world.GetJointCount(), 1);
            EXPECT_EQ(world.GetJointList(), j2);
        } else if (which == 1) {
            world.DestroyJoint(j2);
            ASSERT_EQ(listener.joints.size(), 1u);
            EXPECT_EQ(listener.joints[0], gear);
            EXPECT_EQ(world.GetJointCount(), 1);
        } else {
            // The ground carries j1 and j2 (not the gear): all three go, the gear first.
            world.DestroyBody(ground);
            ASSERT_EQ(listener.joints.size(), 3u);
            EXPECT_EQ(listener.joints[1], gear);
            EXPECT_EQ(world.GetJointCount(), 0);
            EXPECT_EQ(a->GetJointList(), nullptr);
            EXPECT_EQ(b->GetJointList(), nullptr);
        }
        Step(world, 10);  // no dangling reference is touched (ASan would report it)
    }
}

TEST(JointApi, NoJointsNoJointLoops) {
    b2World world(b2Vec2(0, -10));
    Box(world, 0, 5, Fixed(0.5), 1);
    Step(world);
    EXPECT_EQ(world.GetProfile().jointConstraints, 0);
    EXPECT_EQ(world.GetProfile().jointVelocityIterations, 0);
}

TEST(JointApi, StaticAndKinematicJointCostsNothing) {
    b2World world(b2Vec2(0, -10));
    b2Body* s = Ground(world);
    b2Body* s2 = Ground(world);
    b2BodyDef kd;
    kd.type = b2_kinematicBody;
    kd.position.Set(3, 0);
    kd.angularVelocity = 1;  // awake and moving: it seeds an island every step
    b2Body* k = world.CreateBody(&kd);
    b2DistanceJointDef dd;
    dd.Initialize(s, s2, b2Vec2(0, 0), b2Vec2(1, 0));
    world.CreateJoint(&dd);
    b2RevoluteJointDef rd;
    rd.Initialize(s, k, k->GetPosition());
    world.CreateJoint(&rd);
    Step(world, 3);
    EXPECT_EQ(world.GetProfile().jointConstraints, 0);
    EXPECT_EQ(world.GetProfile().jointVelocityIterations, 0);
    EXPECT_EQ(k->GetAngularVelocity(), Fixed(1));
}

TEST(JointApi, JointCountedInProfileWhenPresent) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 1, 5, Fixed(0.5), 1);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, a, b2Vec2(0, 5));
    world.CreateJoint(&rd);
    Step(world);
    EXPECT_EQ(world.GetProfile().jointConstraints, 1);
    EXPECT_EQ(world.GetProfile().jointVelocityIterations, 8);
}

TEST(JointApi, SettersAndGetters) {
    b2World world(b2Vec2(0, -10));
    b2Body* ground = Ground(world);
    b2Body* a = Box(world, 1, 5, Fixed(0.5), 1);
    b2RevoluteJointDef rd;
    rd.Initialize(ground, a, b2Vec2(0, 5));
    auto* r = static_cast<b2RevoluteJoint*>(world.CreateJoint(&rd));
    r->EnableLimit(true);
    r->SetLimits(-1, 1);
    r->EnableMotor(true);
    r->SetMotorSpeed(2);
    r->SetMaxMotorTorque(10);
    EXPECT_TRUE(r->IsLimitEnabled());
    EXPECT_EQ(r->GetLowerLimit(), Fixed(-1));
    EXPECT_EQ(r->GetUpperLimit(), Fixed(1));
    EXPECT_TRUE(r->IsMotorEnabled());
    EXPECT_EQ(r->GetMotorSpeed(), Fixed(2));
    EXPECT_EQ(r->GetMaxMotorTorque(), Fixed(10));
    EXPECT_EQ(r->GetAnchorA(), r->GetAnchorB());
    EXPECT_EQ(r->GetAnchorA(), b2Vec2(0, 5));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::jt
