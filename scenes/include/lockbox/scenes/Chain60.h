#pragma once
/// chain60 (SCENES.md): v2.2.1 testbed Chain with 60 links, hung at y = 65. Edge
/// (-40,0)-(40,0) on the ground body. Link i = 0..59: dynamic at (0.5 + i, 65), 0.6x0.125 half
/// extents, density 20, friction 0.2; b2RevoluteJointDef::Initialize(prev, link, (i, 65)), prev =
/// ground for i = 0, collideConnected false. The chain starts horizontal and swings; it never
/// reaches the ground. Reports the max joint separation (sampled every step). 600 steps, 8/3.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A 60-link chain swinging from a ground pivot.
template <class E>
class Chain60Scene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "chain60", 600, 8, 3, 60, true, true, false, "testbed Chain: 60 links on revolute joints"};
    /// True when engine E has the joint types this scene needs.
    static constexpr bool kAvailable = E::kHasRevolute;
    static constexpr int kLinks = 60;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        if constexpr (kAvailable) {
            typename E::BodyDef groundDef;
            auto* ground = e.world().CreateBody(&groundDef);
            typename E::EdgeShape edge;
            E::SetEdge(edge, E::V(-40, 0), E::V(40, 0));
            ground->CreateFixture(&edge, 0);

            typename E::PolygonShape shape;
            shape.SetAsBox(E::R(6, 10), E::R(1, 8));
            typename E::FixtureDef fd;
            fd.shape = &shape;
            fd.density = 20;
            fd.friction = E::R(2, 10);
            typename E::RevoluteJointDef jd;
            jd.collideConnected = false;
            auto* prev = ground;
            for (int i = 0; i < kLinks; ++i) {
                typename E::BodyDef bd;
                bd.type = E::kDynamic;
                bd.position = E::V(E::R(2 * i + 1, 2), 65);
                auto* body = e.world().CreateBody(&bd);
                body->CreateFixture(&fd);
                jd.Initialize(prev, body, E::V(i, 65));
                e.CreateJoint(jd);
                prev = body;
            }
            last_ = prev;
        }
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        jointSep_ = std::max(jointSep_, MaxJointSeparation(e));
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        out.push_back({"joint_sep", std::max(jointSep_, MaxJointSeparation(e))});
        if (last_) out.push_back({"end_y", E::D(last_->GetPosition().y)});
    }

private:
    double jointSep_ = 0;
    typename E::Body* last_ = nullptr;
};

}  // namespace lockbox::scenes
