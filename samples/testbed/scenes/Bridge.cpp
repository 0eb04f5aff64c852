// bridge (testbed-only, after the v2.2.1 testbed Bridge): thirty planks on revolute joints
// between two ground pivots, with boxes and balls dropped on them.
#include "SceneCatalog.h"
#include "lockbox/dynamics/joints/Joints.h"

namespace lockbox::testbed {

namespace {

using E = scenes::LockboxEngine;

/// Ground edge (-40,0)-(40,0). Planks i = 0..29: 0.5 x 0.125 half extents, density 20,
/// friction 0.2, at (-14.5 + i, 5); revolute joints at (-15 + i, 5) to the previous plank (the
/// ground for i = 0) and a last one at (15, 5) to the ground. Three boxes (0.5 m half size) and
/// three balls (radius 0.5 m), density 1, fall on the bridge from y = 10 and 12.
/// 600 steps, 8/3, 60 Hz.
class BridgeScene : public scenes::LockboxScene {
public:
    static constexpr scenes::SceneInfo kInfo{
        "bridge", 600, 8, 3, 60, true, false, false, "testbed Bridge: 30 planks on revolute joints, loaded"};
    static constexpr int kPlanks = 30;
    const scenes::SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        b2BodyDef groundDef;
        b2Body* ground = e.world().CreateBody(&groundDef);
        b2EdgeShape edge;
        E::SetEdge(edge, E::V(-40, 0), E::V(40, 0));
        ground->CreateFixture(&edge, 0);

        b2PolygonShape plank;
        plank.SetAsBox(E::R(1, 2), E::R(1, 8));
        b2FixtureDef fd;
        fd.shape = &plank;
        fd.density = 20;
        fd.friction = E::R(2, 10);
        b2RevoluteJointDef jd;
        b2Body* prev = ground;
        for (int i = 0; i < kPlanks; ++i) {
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            bd.position = E::V(E::R(-29 + 2 * i, 2), 5);
            b2Body* body = e.world().CreateBody(&bd);
            body->CreateFixture(&fd);
            jd.Initialize(prev, body, E::V(-15 + i, 5));
            e.CreateJoint(jd);
            prev = body;
        }
        jd.Initialize(prev, ground, E::V(-15 + kPlanks, 5));
        e.CreateJoint(jd);

        b2PolygonShape box;
        box.SetAsBox(E::R(1, 2), E::R(1, 2));
        b2CircleShape ball;
        ball.m_radius = E::R(1, 2);
        for (int k = 0; k < 3; ++k) {
            b2FixtureDef load;
            load.density = 1;
            load.friction = E::R(6, 10);
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            load.shape = &box;
            bd.position = E::V(-8 + 8 * k, 10);
            e.world().CreateBody(&bd)->CreateFixture(&load);
            load.shape = &ball;
            bd.position = E::V(-4 + 8 * k, 12);
            e.world().CreateBody(&bd)->CreateFixture(&load);
        }
    }
};

const SceneRegistration kBridgeRegistration("bridge", [] {
    return std::unique_ptr<scenes::LockboxScene>(std::make_unique<BridgeScene>());
});

}  // namespace

}  // namespace lockbox::testbed
