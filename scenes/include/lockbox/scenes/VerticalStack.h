#pragma once
/// vertical_stack (SCENES.md): v2.2.1 testbed VerticalStack, one column of 20 boxes.
/// Ground edges (-40,0)-(40,0) and (20,0)-(20,20) on one static body; boxes 0.5x0.5 half
/// extents, density 1, friction 0.3 at x = 0, y = 0.752 + 1.54 i (they start 0.54 m apart and
/// drop onto each other). Tracks the top box (ideal rest y 19.5 m). 600 steps, 8/3, 60 Hz.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// One column of 20 boxes dropped onto each other.
template <class E>
class VerticalStackScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "vertical_stack", 600, 8, 3, 60, true, true, false, "testbed VerticalStack: a column of 20 boxes"};
    static constexpr int kCount = 20;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::EdgeShape edge;
        E::SetEdge(edge, E::V(-40, 0), E::V(40, 0));
        ground->CreateFixture(&edge, 0);
        E::SetEdge(edge, E::V(20, 0), E::V(20, 20));
        ground->CreateFixture(&edge, 0);

        typename E::PolygonShape box;
        box.SetAsBox(E::R(1, 2), E::R(1, 2));
        typename E::FixtureDef fd;
        fd.shape = &box;
        fd.density = 1;
        fd.friction = E::R(3, 10);
        for (int i = 0; i < kCount; ++i) {
            typename E::BodyDef bd;
            bd.type = E::kDynamic;
            // 0.752 + 1.54 i, rounded once from the exact decimal.
            bd.position = E::V(0, E::R(752 + 1540 * i, 1000));
            top_ = e.world().CreateBody(&bd);
            top_->CreateFixture(&fd);
        }
        tracker_.x0 = 0;
        tracker_.restY = 19.5;
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        tracker_.Observe(E::D(top_->GetPosition().x), E::D(top_->GetPosition().y));
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        tracker_.Observe(E::D(top_->GetPosition().x), E::D(top_->GetPosition().y));
        tracker_.Report(out);
    }

    /// The tracked (top) box.
    typename E::Body* Top() const noexcept { return top_; }

private:
    typename E::Body* top_ = nullptr;
    TopTracker tracker_;
};

}  // namespace lockbox::scenes
