#pragma once
/// tumbler (SCENES.md): Box2D v3 tumbler. A static ground body (no fixture); a dynamic drum
/// at (0, 10) with allowSleep = false and four density-50 boxes: 0.5x10 at (+10, 0), (-10, 0)
/// and 10x0.5 at (0, +10), (0, -10) (local). A revolute joint ground-drum, localAnchorA (0, 10),
/// localAnchorB (0, 0), motor on at 25 deg/s, max torque 1e8 N m (or the engine's largest).
/// 45x45 boxes 0.125x0.125, density 1, friction 0.6 at x = -9 + 0.4 j, y = 1 + 0.4 i (i rows,
/// j columns). `escaped` counts boxes more than 14.2 m from (0, 10). 750 steps, 8/3, sleep on.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A motor-driven drum tumbling 2025 small boxes.
template <class E>
class TumblerScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "tumbler", 750, 8, 3, 60, true, true, false, "v3 tumbler: rotating drum with 2025 boxes"};
    /// True when engine E has the joint types this scene needs.
    static constexpr bool kAvailable = E::kHasRevolute;
    static constexpr int kGrid = 45;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        if constexpr (kAvailable) {
            typename E::BodyDef groundDef;
            auto* ground = e.world().CreateBody(&groundDef);

            typename E::BodyDef drumDef;
            drumDef.type = E::kDynamic;
            drumDef.allowSleep = false;
            drumDef.position = E::V(0, 10);
            auto* drum = e.world().CreateBody(&drumDef);
            typename E::PolygonShape wall;
            wall.SetAsBox(E::R(1, 2), 10, E::V(10, 0), 0);
            drum->CreateFixture(&wall, 50);
            wall.SetAsBox(E::R(1, 2), 10, E::V(-10, 0), 0);
            drum->CreateFixture(&wall, 50);
            wall.SetAsBox(10, E::R(1, 2), E::V(0, 10), 0);
            drum->CreateFixture(&wall, 50);
            wall.SetAsBox(10, E::R(1, 2), E::V(0, -10), 0);
            drum->CreateFixture(&wall, 50);

            typename E::RevoluteJointDef jd;
            jd.bodyA = ground;
            jd.bodyB = drum;
            jd.localAnchorA = E::V(0, 10);
            jd.localAnchorB = E::V(0, 0);
            jd.referenceAngle = 0;
            jd.motorSpeed = E::Deg(25);
            E::SetMaxMotorTorque(jd, 100000000);
            jd.enableMotor = true;
            e.CreateJoint(jd);

            typename E::PolygonShape box;
            box.SetAsBox(E::R(1, 8), E::R(1, 8));
            typename E::FixtureDef fd;
            fd.shape = &box;
            fd.density = 1;
            fd.friction = E::R(6, 10);
            for (int i = 0; i < kGrid; ++i) {
                for (int j = 0; j < kGrid; ++j) {
                    typename E::BodyDef bd;
                    bd.type = E::kDynamic;
                    bd.position = E::V(E::R(-90 + 4 * j, 10), E::R(10 + 4 * i, 10));
                    auto* b = e.world().CreateBody(&bd);
                    b->CreateFixture(&fd);
                    boxes_.push_back(b);
                }
            }
        }
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        int escaped = 0;
        for (auto* b : boxes_) {
            const double dx = E::D(b->GetPosition().x), dy = E::D(b->GetPosition().y) - 10;
            if (dx * dx + dy * dy > 14.2 * 14.2) ++escaped;
        }
        out.push_back({"escaped", static_cast<double>(escaped)});
    }

private:
    std::vector<typename E::Body*> boxes_;
};

}  // namespace lockbox::scenes
