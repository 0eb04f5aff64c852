// A restored world answers joint reaction queries as the saved world did. Several joints'
// GetReactionForce/GetReactionTorque read directions their last solve computed (distance and
// rope: the rope direction; pulley: the rope direction on B; prismatic: the axis and its
// perpendicular; wheel: the suspension and drive axes; gear: its Jacobian). A game that reads
// them between a rollback's restore and the next step (a breakable joint, say) must see the
// values it would have seen without the rollback, on every peer: in place after a discarded
// branch, and in a fresh world after a late join.

#include <vector>

#include <gtest/gtest.h>

#include "StateTestUtil.h"
#include "lockbox/dynamics/joints/Joints.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

b2Body* Box(b2World& world, Fixed x, Fixed y) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(x, y);
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(Fixed(0.25), Fixed(0.25));
    body->CreateFixture(&box, Fixed(1));
    return body;
}

/// One joint of every type, each under load (gravity, motors, springs), none touching.
void BuildJoints(b2World& world) {
    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);

    b2DistanceJointDef dd;
    b2Body* hanging = Box(world, Fixed(-10), Fixed(8));
    dd.Initialize(ground, hanging, b2Vec2(Fixed(-11), Fixed(10)), hanging->GetPosition());
    world.CreateJoint(&dd);

    b2RopeJointDef rope;
    b2Body* swinging = Box(world, Fixed(-7), Fixed(9));
    rope.bodyA = ground;
    rope.bodyB = swinging;
    rope.localAnchorA.Set(Fixed(-8), Fixed(10));
    rope.maxLength = Fixed(2);
    world.CreateJoint(&rope);

    b2PulleyJointDef pd;
    b2Body* left = Box(world, Fixed(-4), Fixed(6));
    b2Body* right = Box(world, Fixed(-2), Fixed(6));
    pd.Initialize(left, right, b2Vec2(Fixed(-4), Fixed(10)), b2Vec2(Fixed(-2), Fixed(10)), left->GetPosition(),
                  right->GetPosition(), Fixed(1.5));
    world.CreateJoint(&pd);

    b2PrismaticJointDef sd;
    b2Body* slider = Box(world, Fixed(1), Fixed(8));
    sd.Initialize(ground, slider, slider->GetPosition(), b2Vec2(Fixed(0.6), Fixed(0.8)));
    sd.enableMotor = true;
    sd.motorSpeed = Fixed(1);
    sd.maxMotorForce = Fixed(30);
    b2Joint* prismatic = world.CreateJoint(&sd);

    b2RevoluteJointDef rd;
    b2Body* wheel = Box(world, Fixed(4), Fixed(8));
    rd.Initialize(ground, wheel, wheel->GetPosition());
    b2Joint* revolute = world.CreateJoint(&rd);

    b2GearJointDef gd;
    gd.bodyA = wheel;
    gd.bodyB = slider;
    gd.joint1 = revolute;
    gd.joint2 = prismatic;
    gd.ratio = Fixed(2);
    world.CreateJoint(&gd);

    b2WheelJointDef wd;
    b2Body* chassis = Box(world, Fixed(8), Fixed(8));
    b2Body* tyre = Box(world, Fixed(8), Fixed(7));
    wd.Initialize(chassis, tyre, tyre->GetPosition(), b2Vec2(Fixed(0.3), Fixed(1)));
    wd.enableMotor = true;
    wd.motorSpeed = Fixed(-3);
    wd.maxMotorTorque = Fixed(5);
    wd.frequencyHz = Fixed(4);
    wd.dampingRatio = Fixed(0.7);
    world.CreateJoint(&wd);
    b2RevoluteJointDef hold;
    hold.Initialize(ground, chassis, chassis->GetPosition());
    world.CreateJoint(&hold);

    b2WeldJointDef weld;
    b2Body* a = Box(world, Fixed(12), Fixed(8));
    b2Body* b = Box(world, Fixed(12.5), Fixed(8));
    weld.Initialize(a, b, b2Vec2(Fixed(12.25), Fixed(8)));
    world.CreateJoint(&weld);
    b2RevoluteJointDef pin;
    pin.Initialize(ground, a, a->GetPosition());
    world.CreateJoint(&pin);

    b2FrictionJointDef fd;
    b2Body* sliding = Box(world, Fixed(15), Fixed(8));
    fd.Initialize(ground, sliding, sliding->GetPosition());
    fd.maxForce = Fixed(2);
    fd.maxTorque = Fixed(1);
    world.CreateJoint(&fd);

    b2MouseJointDef md;
    b2Body* dragged = Box(world, Fixed(18), Fixed(8));
    md.bodyA = ground;
    md.bodyB = dragged;
    md.target.Set(Fixed(19), Fixed(9));
    md.maxForce = Wide(50);
    world.CreateJoint(&md);
}

struct Reaction {
    b2JointType type;
    b2Vec2 force;
    Fixed torque;
};

std::vector<Reaction> Reactions(b2World& world) {
    const Fixed invDt(60);
    std::vector<Reaction> out;
    for (b2Joint* j = world.GetJointList(); j; j = j->GetNext())
        out.push_back({j->GetType(), j->GetReactionForce(invDt), j->GetReactionTorque(invDt)});
    return out;
}

::testing::AssertionResult SameReactions(const std::vector<Reaction>& expected, const std::vector<Reaction>& actual) {
    if (expected.size() != actual.size()) return ::testing::AssertionFailure() << "joint counts differ";
    for (size_t i = 0; i < expected.size(); ++i) {
        const Reaction& e = expected[i];
        const Reaction& a = actual[i];
        if (e.type != a.type || e.force != a.force || e.torque != a.torque) {
            return ::testing::AssertionFailure()
                   << "joint " << i << " (type " << e.type << "): force (" << e.force.x.Raw() << ", " << e.force.y.Raw()
                   << ") torque " << e.torque.Raw() << " expected, got (" << a.force.x.Raw() << ", " << a.force.y.Raw()
                   << ") torque " << a.torque.Raw();
        }
    }
    return ::testing::AssertionSuccess();
}

void Step(b2World& world, int n) {
    for (int i = 0; i < n; ++i) world.Step(Fixed::FromRaw(1092), 8, 3);
}

TEST(JointReactionRestore, AfterADiscardedBranchInPlace) {
    b2World world(b2Vec2(Fixed(0), Fixed(-10)));
    BuildJoints(world);
    Step(world, 30);
    const std::vector<uint8> image = world.Save();
    const std::vector<Reaction> saved = Reactions(world);
    // Every reaction the test compares is a real load, not a zero that any state would give.
    int loaded = 0;
    for (const Reaction& r : saved) loaded += (r.force != b2Vec2_zero || r.torque != Fixed()) ? 1 : 0;
    ASSERT_GE(loaded, 10);

    // A mispredicted branch: every body kicked, 12 frames.
    for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() == b2_dynamicBody) b->SetLinearVelocity(b->GetLinearVelocity() + b2Vec2(Fixed(3), Fixed(2)));
    }
    Step(world, 12);
    ASSERT_FALSE(SameReactions(saved, Reactions(world))) << "the branch should move every reaction";

    const b2RestoreResult r = world.Restore(image);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_TRUE(SameReactions(saved, Reactions(world)));
}

TEST(JointReactionRestore, InAFreshWorld) {
    b2World world(b2Vec2(Fixed(0), Fixed(-10)));
    BuildJoints(world);
    Step(world, 30);
    const std::vector<uint8> image = world.Save();

    b2World joiner(b2Vec2(Fixed(0), Fixed(0)));
    const b2RestoreResult r = joiner.Restore(image);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_TRUE(SameReactions(Reactions(world), Reactions(joiner)));
    // And the two stay together.
    Step(world, 5);
    Step(joiner, 5);
    EXPECT_TRUE(SameReactions(Reactions(world), Reactions(joiner)));
    EXPECT_EQ(world.Hash(), joiner.Hash());
}

// Format 3 changed the body record: images of formats 1 and 2 (written under an older
// determinism version too) and of a format this build does not know are refused by name.
TEST(JointReactionRestore, OtherFormatsAreRefusedByName) {
    b2World world(b2Vec2(Fixed(0), Fixed(-10)));
    BuildJoints(world);
    Step(world, 30);
    const std::vector<uint8> image = world.Save();
    for (const uint8 format : {uint8{1}, uint8{2}, uint8{4}}) {
        std::vector<uint8> other = image;
        other[5] = format;  // format version (u16 at offset 5)
        other[6] = 0;
        b2SealSnapshot(other);
        b2World joiner(b2Vec2(Fixed(0), Fixed(0)));
        const b2RestoreResult refused = joiner.Restore(other);
        EXPECT_EQ(refused.error, b2SnapshotError::e_badFormatVersion) << int{format} << ": " << refused.message;
        EXPECT_EQ(joiner.GetBodyCount(), 0) << "a refused image leaves the world untouched";
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
