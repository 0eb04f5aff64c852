#pragma once
/// bullet (SCENES.md): six 60-step variants, target {wall, stack} x mode {dynamic, bullet,
/// dynamic with continuous physics off}. Edge (-20,0)-(60,0). Wall: static body at (10, 5),
/// 0.05x5 half extents. Stack: ten dynamic 0.5x0.5 boxes at (10, 0.5 + i), density 1, friction
/// 0.6. Projectile: 0.125x0.125 box, density 1, friction 0.6, from (0.9, 2.5) at (300, 0) m/s;
/// the 2 m per-step translation clamp makes it fly at 120 m/s at 60 Hz, so no discrete position
/// lands on the target. `touched`: a contact began between projectile and target; `tunneled`:
/// the projectile's back face passed the target's far face without touching it.

#include <string_view>

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// What the projectile is shot at.
enum class BulletTarget { wall, stack };
/// How the projectile is simulated.
enum class BulletMode { dynamic, bullet, noContinuous };

/// One bullet variant.
template <class E>
class BulletScene : public Scene<E> {
public:
    static constexpr SceneInfo kInfos[6] = {
        {"bullet_wall_dynamic", 60, 8, 3, 60, true, true, false, "projectile vs wall, dynamic"},
        {"bullet_wall_bullet", 60, 8, 3, 60, true, true, false, "projectile vs wall, bullet flag"},
        {"bullet_wall_nocontinuous", 60, 8, 3, 60, true, true, false, "projectile vs wall, continuous physics off"},
        {"bullet_stack_dynamic", 60, 8, 3, 60, true, true, false, "projectile vs stack, dynamic"},
        {"bullet_stack_bullet", 60, 8, 3, 60, true, true, false, "projectile vs stack, bullet flag"},
        {"bullet_stack_nocontinuous", 60, 8, 3, 60, true, true, false, "projectile vs stack, continuous physics off"},
    };
    /// One of the six variants.
    BulletScene(BulletTarget target, BulletMode mode) : target_(target), mode_(mode) {}
    /// The defaults above.
    const SceneInfo& Info() const override {
        return kInfos[(target_ == BulletTarget::wall ? 0 : 3) + static_cast<int>(mode_)];
    }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::EdgeShape edge;
        E::SetEdge(edge, E::V(-20, 0), E::V(60, 0));
        ground->CreateFixture(&edge, 0);

        if (target_ == BulletTarget::wall) {
            typename E::BodyDef bd;
            bd.position = E::V(10, 5);
            auto* wall = e.world().CreateBody(&bd);
            typename E::PolygonShape box;
            box.SetAsBox(E::R(5, 100), 5);
            wall->CreateFixture(&box, 0);
            targets_.push_back(wall);
            farFace_ = 10.05;
        } else {
            typename E::PolygonShape box;
            box.SetAsBox(E::R(1, 2), E::R(1, 2));
            typename E::FixtureDef fd;
            fd.shape = &box;
            fd.density = 1;
            fd.friction = E::R(6, 10);
            for (int i = 0; i < 10; ++i) {
                typename E::BodyDef bd;
                bd.type = E::kDynamic;
                bd.position = E::V(10, E::R(2 * i + 1, 2));
                auto* b = e.world().CreateBody(&bd);
                b->CreateFixture(&fd);
                targets_.push_back(b);
            }
            farFace_ = 10.5;
        }

        typename E::BodyDef bd;
        bd.type = E::kDynamic;
        bd.position = E::V(E::R(9, 10), E::R(5, 2));
        bd.linearVelocity = E::V(300, 0);
        bd.bullet = mode_ == BulletMode::bullet;
        projectile_ = e.world().CreateBody(&bd);
        typename E::PolygonShape box;
        box.SetAsBox(E::R(1, 8), E::R(1, 8));
        typename E::FixtureDef fd;
        fd.shape = &box;
        fd.density = 1;
        fd.friction = E::R(6, 10);
        projectile_->CreateFixture(&fd);
        if (mode_ == BulletMode::noContinuous) e.world().SetContinuousPhysics(false);

        e.onBeginContact = [this](typename E::Contact* c) {
            auto* a = c->GetFixtureA()->GetBody();
            auto* b = c->GetFixtureB()->GetBody();
            if (a != projectile_ && b != projectile_) return;
            auto* other = a == projectile_ ? b : a;
            for (auto* t : targets_)
                if (t == other) touched_ = true;
        };
        e.InstallListener();
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        Check();
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        Check();
        out.push_back({"touched", touched_ ? 1.0 : 0.0});
        out.push_back({"tunneled", tunneled_ ? 1.0 : 0.0});
        out.push_back({"projectile_x", E::D(projectile_->GetPosition().x)});
    }

    /// True once a contact began between projectile and target.
    bool Touched() const noexcept { return touched_; }
    /// True once the projectile passed the target without touching it.
    bool Tunneled() const noexcept { return tunneled_; }

private:
    void Check() {
        const double back = E::D(projectile_->GetPosition().x) - 0.125;
        if (!touched_ && back > farFace_) tunneled_ = true;
    }

    BulletTarget target_;
    BulletMode mode_;
    std::vector<typename E::Body*> targets_;
    typename E::Body* projectile_ = nullptr;
    double farFace_ = 0;  ///< x of the target's far face, m
    bool touched_ = false;
    bool tunneled_ = false;
};

}  // namespace lockbox::scenes
