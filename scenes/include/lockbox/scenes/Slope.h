#pragma once
/// slope (lockbox's own, for the accuracy study): a box slides down a 3:4 slope (sin 0.6,
/// cos 0.8, about 36.87 deg) with friction 0.2 on both fixtures (mixed sqrt(0.2 * 0.2) = 0.2).
/// The analytic acceleration along the slope is g (sin - mu cos) = 10 (0.6 - 0.16) = 4.4 m/s^2.
/// The slope is the edge (-20, 15)-(20, -15); the box (0.5 m half extents, density 1) is a
/// polygon whose vertices are rotated onto the slope, its body angle 0, resting on the edge at
/// x = -15. Reports the measured acceleration (from the along-slope speed between 0.5 s and
/// 1.5 s) and its relative error. 120 steps at 60 Hz (the driver scales steps with Hz).

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A box sliding down a slope with Coulomb friction.
template <class E>
class SlopeScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "slope", 120, 8, 3, 60, true, false, false, "box sliding on a 3:4 slope, analytic a = 4.4 m/s^2"};
    static constexpr double kTrueAcceleration = 4.4;  ///< g (sin - mu cos), m/s^2
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::EdgeShape edge;
        E::SetEdge(edge, E::V(-20, 15), E::V(20, -15));
        typename E::FixtureDef gfd;
        gfd.shape = &edge;
        gfd.friction = E::R(2, 10);
        ground->CreateFixture(&gfd);

        // Down-slope direction d = (0.8, -0.6), outward normal n = (0.6, 0.8); corners
        // +-0.5 d +-0.5 n, all multiples of 0.1 m.
        const typename E::Vec corners[4] = {E::V(E::R(1, 10), E::R(-7, 10)), E::V(E::R(7, 10), E::R(1, 10)),
                                            E::V(E::R(-1, 10), E::R(7, 10)), E::V(E::R(-7, 10), E::R(-1, 10))};
        typename E::PolygonShape box;
        box.Set(corners, 4);
        typename E::BodyDef bd;
        bd.type = E::kDynamic;
        // On the edge at x = -15 (y = 11.25), lifted 0.52 m along n (half extent plus the two 0.01 m skins).
        bd.position = E::V(E::R(-15 * 1000 + 312, 1000), E::R(11250 + 416, 1000));
        box_ = e.world().CreateBody(&bd);
        typename E::FixtureDef fd;
        fd.shape = &box;
        fd.density = 1;
        fd.friction = E::R(2, 10);
        box_->CreateFixture(&fd);
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        const int hz = this->run_.hz;
        const double v = 0.8 * E::D(box_->GetLinearVelocity().x) - 0.6 * E::D(box_->GetLinearVelocity().y);
        if (step + 1 == hz / 2) v1_ = v;
        if (step + 1 == (3 * hz) / 2) v2_ = v;
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        // The samples are hz steps apart: hz * dt seconds (dt = round(65536/hz)/65536).
        const double a = (v2_ - v1_) / (this->run_.hz * this->StepSeconds());
        out.push_back({"slide_accel", a});
        out.push_back({"slide_accel_err", std::fabs(a - kTrueAcceleration) / kTrueAcceleration});
    }

private:
    typename E::Body* box_ = nullptr;
    double v1_ = 0, v2_ = 0;
};

}  // namespace lockbox::scenes
