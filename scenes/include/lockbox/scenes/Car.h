#pragma once
/// car (lockbox's own, after the v2.2.1 testbed Car): a chassis on two wheel joints (axis
/// (0, 1), spring 4 Hz, damping ratio 0.7) drives over a chain-shape terrain of hills. Terrain:
/// one open b2ChainShape through x = -20..200 every 5 m, flat up to x = 0, then heights
/// cycling through {0, 0.25, 1, 1.25, 0, 0, -1, -2, -1.25, 0} m. Chassis: a six-vertex polygon (density 1) at
/// (0, 1); wheels: circles of radius 0.4 (density 1, friction 0.9) at (-1, 0.35) and (1, 0.4);
/// the rear wheel's motor turns at -10 rad/s with at most 20 N m. 600 steps, 8/3, 60 Hz.
/// Reports how far the car got (car_x), its final tilt and the usual max_pen.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A car on wheel-joint suspension over chain terrain.
template <class E>
class CarScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "car", 600, 8, 3, 60, true, false, false, "car on wheel-joint springs over chain-shape hills"};
    /// True when engine E has the joint types this scene needs.
    static constexpr bool kAvailable = E::kHasWheel;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        if constexpr (kAvailable) {
            typename E::BodyDef groundDef;
            auto* ground = e.world().CreateBody(&groundDef);
            // Heights in quarter metres, repeating every 10 samples (50 m).
            constexpr int kHeights[10] = {0, 1, 4, 5, 0, 0, -4, -8, -5, 0};
            std::vector<typename E::Vec> points;
            for (int i = 0; i <= 44; ++i) {
                const int h = i < 4 ? 0 : kHeights[(i - 4) % 10];
                points.push_back(E::V(-20 + 5 * i, E::R(h, 4)));
            }
            typename E::ChainShape chain;
            E::CreateChain(chain, points.data(), static_cast<int>(points.size()));
            typename E::FixtureDef gfd;
            gfd.shape = &chain;
            gfd.friction = E::R(6, 10);
            ground->CreateFixture(&gfd);

            const typename E::Vec hull[6] = {
                E::V(E::R(-3, 2), E::R(-1, 2)), E::V(E::R(3, 2), E::R(-1, 2)),    E::V(E::R(3, 2), 0),
                E::V(0, E::R(9, 10)),           E::V(E::R(-23, 20), E::R(9, 10)), E::V(E::R(-3, 2), E::R(1, 5))};
            typename E::PolygonShape chassis;
            chassis.Set(hull, 6);
            typename E::BodyDef bd;
            bd.type = E::kDynamic;
            bd.position = E::V(0, 1);
            car_ = e.world().CreateBody(&bd);
            car_->CreateFixture(&chassis, 1);

            typename E::CircleShape wheel;
            wheel.m_radius = E::R(2, 5);
            typename E::FixtureDef wfd;
            wfd.shape = &wheel;
            wfd.density = 1;
            wfd.friction = E::R(9, 10);
            const typename E::Vec wheelPos[2] = {E::V(-1, E::R(7, 20)), E::V(1, E::R(2, 5))};
            for (int k = 0; k < 2; ++k) {
                typename E::BodyDef wd;
                wd.type = E::kDynamic;
                wd.position = wheelPos[k];
                auto* w = e.world().CreateBody(&wd);
                w->CreateFixture(&wfd);
                typename E::WheelJointDef jd;
                jd.Initialize(car_, w, w->GetPosition(), E::V(0, 1));
                jd.motorSpeed = -10;
                E::SetMaxMotorTorque(jd, k == 0 ? 20 : 0);
                jd.enableMotor = k == 0;
                E::SetWheelSpring(jd, 4, E::R(7, 10));
                e.CreateJoint(jd);
            }
        }
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        if (!car_) return;
        out.push_back({"car_x", E::D(car_->GetPosition().x)});
        out.push_back({"car_angle", E::D(car_->GetAngle())});
    }

private:
    typename E::Body* car_ = nullptr;
};

}  // namespace lockbox::scenes
