#pragma once
/// hello (SCENES.md): the v2.2.1 manual's Hello World. A 1x1 m half-extent box (density 1,
/// friction 0.3) falls from (0, 4) onto a static 50x10 ground box centred at (0, -10).
/// 60 steps, 6/2 iterations, 60 Hz, sleep on. Reports the box's final x, y and angle.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// The manual's Hello World.
template <class E>
class HelloScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "hello", 60, 6, 2, 60, true, true, false, "manual Hello World: one box falls on a ground box"};
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        groundDef.position.Set(0, -10);
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::PolygonShape groundBox;
        groundBox.SetAsBox(50, 10);
        ground->CreateFixture(&groundBox, 0);

        typename E::BodyDef bodyDef;
        bodyDef.type = E::kDynamic;
        bodyDef.position.Set(0, 4);
        body_ = e.world().CreateBody(&bodyDef);
        typename E::PolygonShape box;
        box.SetAsBox(1, 1);
        typename E::FixtureDef fd;
        fd.shape = &box;
        fd.density = 1;
        fd.friction = E::R(3, 10);
        body_->CreateFixture(&fd);
    }

    /// The falling body (for printing x, y, angle as the manual does).
    typename E::Body* Box() const noexcept { return body_; }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        out.push_back({"x", E::D(body_->GetPosition().x)});
        out.push_back({"y", E::D(body_->GetPosition().y)});
        out.push_back({"angle", E::D(body_->GetAngle())});
    }

private:
    typename E::Body* body_ = nullptr;
};

}  // namespace lockbox::scenes
