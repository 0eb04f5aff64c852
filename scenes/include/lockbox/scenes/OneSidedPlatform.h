#pragma once
/// one_sided_platform (lockbox's own, after the v2.2.1 testbed OneSidedPlatform): a static
/// 3x0.5 half-extent platform at (0, 10) over a ground edge (-20,0)-(20,0). Two circle actors
/// of radius 0.5, density 20: A drops from (0, 12) at (0, -50) m/s and must land on top; B
/// starts below at (1.5, 5) moving up at (0, 15) m/s, must pass through the platform and land
/// on it. PreSolve disables a contact while the actor's centre is below
/// top + radius - 3 linearSlop (the testbed rule). 300 steps, 8/3, 60 Hz, sleep on.
/// Reports on_top: the number of actors resting on the platform at the end (2 is right).

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// One-way platform through a PreSolve contact listener.
template <class E>
class OneSidedPlatformScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{"one_sided_platform",
                                     300,
                                     8,
                                     3,
                                     60,
                                     true,
                                     false,
                                     false,
                                     "PreSolve one-way platform: one actor drops on, one jumps through"};
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::EdgeShape edge;
        E::SetEdge(edge, E::V(-20, 0), E::V(20, 0));
        ground->CreateFixture(&edge, 0);

        typename E::BodyDef platformDef;
        platformDef.position = E::V(0, 10);
        auto* platform = e.world().CreateBody(&platformDef);
        typename E::PolygonShape box;
        box.SetAsBox(3, E::R(1, 2));
        platform_ = platform->CreateFixture(&box, 0);
        top_ = E::R(21, 2);

        typename E::CircleShape circle;
        circle.m_radius = E::R(1, 2);
        radius_ = circle.m_radius;
        const typename E::Vec starts[2] = {E::V(0, 12), E::V(E::R(3, 2), 5)};
        const typename E::Vec velocities[2] = {E::V(0, -50), E::V(0, 15)};
        for (int k = 0; k < 2; ++k) {
            typename E::BodyDef bd;
            bd.type = E::kDynamic;
            bd.position = starts[k];
            actors_[k] = e.world().CreateBody(&bd);
            actorFixtures_[k] = actors_[k]->CreateFixture(&circle, 20);
            actors_[k]->SetLinearVelocity(velocities[k]);
        }

        e.onPreSolve = [this](typename E::Contact* c, const typename E::Manifold*) {
            auto* fa = c->GetFixtureA();
            auto* fb = c->GetFixtureB();
            if (fa != platform_ && fb != platform_) return;
            auto* other = fa == platform_ ? fb : fa;
            for (int k = 0; k < 2; ++k) {
                if (other != actorFixtures_[k]) continue;
                // 3 linearSlop (0.015 m) below the resting height: the testbed's margin, so
                // an actor resting on the skin is never mistaken for one coming from below.
                const auto limit = top_ + radius_ - E::R(15, 1000);
                if (actors_[k]->GetPosition().y < limit) c->SetEnabled(false);
            }
        };
        e.InstallListener();
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        int onTop = 0;
        for (auto* a : actors_) {
            const double x = E::D(a->GetPosition().x), y = E::D(a->GetPosition().y);
            if (x > -3 && x < 3 && std::fabs(y - 11.0) < 0.05) ++onTop;
        }
        out.push_back({"on_top", static_cast<double>(onTop)});
    }

private:
    typename E::Fixture* platform_ = nullptr;
    typename E::Body* actors_[2] = {nullptr, nullptr};
    typename E::Fixture* actorFixtures_[2] = {nullptr, nullptr};
    typename E::Num top_{}, radius_{};
};

}  // namespace lockbox::scenes
