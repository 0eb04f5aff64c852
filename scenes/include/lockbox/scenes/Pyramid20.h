#pragma once
/// pyramid20 (SCENES.md): v2.2.1 testbed Pyramid with e_count = 20 (210 boxes). Edge
/// (-40,0)-(40,0); boxes 0.5x0.5 half extents, density 5, friction 0.2. Row i = 0..19 starts at
/// (-7, 0.75) + i (0.5625, 1.25) and holds 20 - i boxes spaced 1.125 m (0.125 m gaps; each row
/// drops 0.25 m). All these numbers are exact in binary. Tracks the apex (ideal rest y 19.5).

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// The 20-row testbed pyramid.
template <class E>
class Pyramid20Scene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "pyramid20", 600, 8, 3, 60, true, true, false, "testbed Pyramid: 210 boxes with gaps"};
    static constexpr int kCount = 20;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::EdgeShape edge;
        E::SetEdge(edge, E::V(-40, 0), E::V(40, 0));
        ground->CreateFixture(&edge, 0);

        typename E::PolygonShape box;
        box.SetAsBox(E::R(1, 2), E::R(1, 2));
        for (int i = 0; i < kCount; ++i) {
            for (int j = i; j < kCount; ++j) {
                typename E::BodyDef bd;
                bd.type = E::kDynamic;
                // x = -7 + 0.5625 i + 1.125 (j - i), y = 0.75 + 1.25 i (in 1/16 m units).
                bd.position = E::V(E::R(-112 + 9 * i + 18 * (j - i), 16), E::R(12 + 20 * i, 16));
                apex_ = e.world().CreateBody(&bd);
                apex_->CreateFixture(&box, 5);
            }
        }
        tracker_.x0 = E::D(apex_->GetPosition().x);
        tracker_.restY = 19.5;
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        tracker_.Observe(E::D(apex_->GetPosition().x), E::D(apex_->GetPosition().y));
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        tracker_.Observe(E::D(apex_->GetPosition().x), E::D(apex_->GetPosition().y));
        tracker_.Report(out);
    }

    /// The tracked apex box.
    typename E::Body* Apex() const noexcept { return apex_; }

private:
    typename E::Body* apex_ = nullptr;
    TopTracker tracker_;
};

}  // namespace lockbox::scenes
