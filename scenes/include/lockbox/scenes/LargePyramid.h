#pragma once
/// large_pyramid (SCENES.md): Box2D v3 benchmark large_pyramid, 100 rows, 5050 boxes. Static
/// body at (0, -1) with a 100x1 half-extent box; boxes 0.5x0.5, density 1, friction 0.6; row
/// i = 0..99, j = i..99 at x = (i+1) 0.5 + (j-i) 1.0 - 50, y = (2i+1) 0.5 (touching, no gaps).
/// Sleep off as in v3. 500 steps, 8/3, 60 Hz. Tracks the apex (ideal rest y 99.5).

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A touching pyramid of `base` rows (100 in SCENES.md; smaller bases for quick tests).
template <class E>
class LargePyramidScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "large_pyramid", 500, 8, 3, 60, false, true, true, "v3 large_pyramid: 5050 touching boxes, sleep off"};
    /// base: number of rows (1..100).
    explicit LargePyramidScene(int base = 100) : base_(base) {}
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        groundDef.position = E::V(0, -1);
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::PolygonShape groundBox;
        groundBox.SetAsBox(100, 1);
        ground->CreateFixture(&groundBox, 0);

        typename E::PolygonShape box;
        box.SetAsBox(E::R(1, 2), E::R(1, 2));
        typename E::FixtureDef fd;
        fd.shape = &box;
        fd.density = 1;
        fd.friction = E::R(6, 10);
        for (int i = 0; i < base_; ++i) {
            for (int j = i; j < base_; ++j) {
                typename E::BodyDef bd;
                bd.type = E::kDynamic;
                // In half metres: x = (i+1) + 2(j-i) - 100, y = 2i + 1.
                bd.position = E::V(E::R((i + 1) + 2 * (j - i) - 100, 2), E::R(2 * i + 1, 2));
                apex_ = e.world().CreateBody(&bd);
                apex_->CreateFixture(&fd);
            }
        }
        tracker_.x0 = E::D(apex_->GetPosition().x);
        tracker_.restY = base_ - 0.5;
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

private:
    int base_;
    typename E::Body* apex_ = nullptr;
    TopTracker tracker_;
};

}  // namespace lockbox::scenes
