#pragma once
/// rain (SCENES.md, lockbox's own definition): a container of edges (-25,0)-(25,0),
/// (-25,0)-(-25,50), (25,0)-(25,50). Before step s (0-based), when s % 8 == 0 and fewer than
/// 2000 bodies were spawned, row r = s / 8 spawns 25 bodies at x = -24 + 2k + 0.5 (r % 2),
/// y = 45, k = 0..24, moving at (0, -10) m/s: a circle of radius 0.4 when k + r is even, else a
/// 0.4x0.4 box; density 1, friction 0.6. 80 rows (steps 0..632), 2000 bodies; 1000 steps, 8/3.
/// `escaped` counts bodies outside the container.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// Bodies raining into a box.
template <class E>
class RainScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "rain", 1000, 8, 3, 60, true, true, false, "2000 circles and boxes rain into a container"};
    static constexpr int kPerRow = 25;
    static constexpr int kMaxBodies = 2000;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::EdgeShape edge;
        E::SetEdge(edge, E::V(-25, 0), E::V(25, 0));
        ground->CreateFixture(&edge, 0);
        E::SetEdge(edge, E::V(-25, 0), E::V(-25, 50));
        ground->CreateFixture(&edge, 0);
        E::SetEdge(edge, E::V(25, 0), E::V(25, 50));
        ground->CreateFixture(&edge, 0);
    }

    void BeforeStep(E& e, int step) override {
        // The spawn schedule depends on the step alone (no counter), so rolling the world back
        // and replaying steps needs no scene state (sync tests, replays).
        const int r = step / 8;
        if (step % 8 != 0 || r >= kMaxBodies / kPerRow) return;
        typename E::CircleShape circle;
        circle.m_radius = E::R(4, 10);
        typename E::PolygonShape box;
        box.SetAsBox(E::R(4, 10), E::R(4, 10));
        typename E::FixtureDef fd;
        fd.density = 1;
        fd.friction = E::R(6, 10);
        for (int k = 0; k < kPerRow; ++k) {
            typename E::BodyDef bd;
            bd.type = E::kDynamic;
            // x = -24 + 2k + 0.5 (r % 2), in half metres.
            bd.position = E::V(E::R(-48 + 4 * k + (r % 2), 2), 45);
            bd.linearVelocity = E::V(0, -10);
            auto* body = e.world().CreateBody(&bd);
            if ((k + r) % 2 == 0) {
                fd.shape = &circle;
            } else {
                fd.shape = &box;
            }
            body->CreateFixture(&fd);
        }
        lastStep_ = step;
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        int escaped = 0;
        for (auto* b = e.world().GetBodyList(); b; b = b->GetNext()) {
            if (b->GetType() != E::kDynamic) continue;
            const double x = E::D(b->GetPosition().x), y = E::D(b->GetPosition().y);
            if (x < -25 || x > 25 || y < 0) ++escaped;
        }
        const int rows = lastStep_ < 0 ? 0 : std::min(lastStep_ / 8 + 1, kMaxBodies / kPerRow);
        out.push_back({"spawned", static_cast<double>(rows * kPerRow)});
        out.push_back({"escaped", static_cast<double>(escaped)});
    }

private:
    int lastStep_ = -1;  ///< the last spawning step (reporting only)
};

}  // namespace lockbox::scenes
