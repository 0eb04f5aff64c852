// dominoes (testbed-only): a ball rolls down a ramp into a row of twenty dominoes.
//
// This file is also the pattern for testbed-only scenes: a scenes::LockboxScene subclass plus
// one namespace-scope SceneRegistration; the build picks up every .cpp in this folder.
#include "SceneCatalog.h"

namespace lockbox::testbed {

namespace {

using E = scenes::LockboxEngine;

/// Ground edge (-40,0)-(40,0); a ramp edge from (-22,12) down to (-8,0); twenty 0.2 x 2 m
/// dominoes (density 1, friction 0.6) standing 1 m apart from x = -4; a ball of radius 0.5 m
/// (density 2, friction 0.6) released at the top of the ramp. 600 steps, 8/3, 60 Hz.
class DominoesScene : public scenes::LockboxScene {
public:
    static constexpr scenes::SceneInfo kInfo{
        "dominoes", 600, 8, 3, 60, true, false, false, "a ball rolls down a ramp into twenty dominoes"};
    const scenes::SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        b2BodyDef groundDef;
        b2Body* ground = e.world().CreateBody(&groundDef);
        b2EdgeShape edge;
        E::SetEdge(edge, E::V(-40, 0), E::V(40, 0));
        ground->CreateFixture(&edge, 0);
        E::SetEdge(edge, E::V(-22, 12), E::V(-8, 0));
        ground->CreateFixture(&edge, 0);

        b2PolygonShape domino;
        domino.SetAsBox(E::R(1, 10), 1);
        b2FixtureDef fd;
        fd.shape = &domino;
        fd.density = 1;
        fd.friction = E::R(6, 10);
        for (int i = 0; i < 20; ++i) {
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            bd.position = E::V(-4 + i, 1);
            e.world().CreateBody(&bd)->CreateFixture(&fd);
        }

        b2CircleShape ball;
        ball.m_radius = E::R(1, 2);
        b2FixtureDef bf;
        bf.shape = &ball;
        bf.density = 2;
        bf.friction = E::R(6, 10);
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position = E::V(-21, 12);
        e.world().CreateBody(&bd)->CreateFixture(&bf);
    }
};

const SceneRegistration kDominoesRegistration("dominoes", [] {
    return std::unique_ptr<scenes::LockboxScene>(std::make_unique<DominoesScene>());
});

}  // namespace

}  // namespace lockbox::testbed
