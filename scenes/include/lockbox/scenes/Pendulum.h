#pragma once
/// pendulum (lockbox's own, for the accuracy study): a disc of radius 0.25 m (density 1) on a
/// revolute joint to a static pivot at (0, 20), arm length L = 5 m, released from rest at
/// 36.87 deg (sin 0.6, cos 0.8: the bob starts at (3, 16)). The exact period of this physical
/// pendulum is T = 2 pi sqrt(I / (m g L)) / AGM(1, cos(theta0 / 2)) with I = m (r^2 / 2 + L^2)
/// about the pivot. Reports the measured period (mean over full swings, from the times the bob
/// crosses x = 0 moving left, interpolated inside a step), its relative error, and the energy
/// drift (relative change of the mechanical energy from start to end). 900 steps at 60 Hz
/// (15 s, three periods); the accuracy driver scales steps with Hz.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A rigid pendulum with an analytic period.
template <class E>
class PendulumScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "pendulum", 900, 8, 3, 60, true, false, false, "disc pendulum on a revolute joint, analytic period"};
    /// True when engine E has the joint types this scene needs.
    static constexpr bool kAvailable = E::kHasRevolute;
    static constexpr double kRadius = 0.25, kLength = 5, kG = 10;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    /// The exact period, s.
    static double TruePeriod() {
        const double pi = 3.14159265358979323846;
        const double theta0 = std::atan2(0.6, 0.8);
        double a = 1, b = std::cos(theta0 / 2);
        for (int i = 0; i < 8; ++i) {
            const double an = (a + b) / 2;
            b = std::sqrt(a * b);
            a = an;
        }
        const double inertiaOverMass = kRadius * kRadius / 2 + kLength * kLength;
        return 2 * pi * std::sqrt(inertiaOverMass / (kG * kLength)) / a;
    }

    void Build(E& e) override {
        if constexpr (kAvailable) {
            typename E::BodyDef groundDef;
            auto* ground = e.world().CreateBody(&groundDef);
            typename E::BodyDef bd;
            bd.type = E::kDynamic;
            bd.position = E::V(3, 16);
            bob_ = e.world().CreateBody(&bd);
            typename E::CircleShape circle;
            circle.m_radius = E::R(1, 4);
            bob_->CreateFixture(&circle, 1);
            typename E::RevoluteJointDef jd;
            jd.Initialize(ground, bob_, E::V(0, 20));
            e.CreateJoint(jd);
            energy0_ = Energy();
        }
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        if (!bob_) return;
        const double x = E::D(bob_->GetPosition().x);
        if (prevX_ > 0 && x <= 0) {
            // Linear interpolation of the crossing inside the step.
            const double frac = prevX_ / (prevX_ - x);
            crossings_.push_back((step + frac) * this->StepSeconds());
        }
        prevX_ = x;
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        double period = 0;
        if (crossings_.size() >= 2)
            period = (crossings_.back() - crossings_.front()) / static_cast<double>(crossings_.size() - 1);
        const double truth = TruePeriod();
        out.push_back({"period", period});
        out.push_back({"period_err", period > 0 ? std::fabs(period - truth) / truth : 1.0});
        out.push_back({"energy_drift", bob_ ? std::fabs(Energy() - energy0_) / std::fabs(energy0_) : 0.0});
        out.push_back({"joint_sep", MaxJointSeparation(e)});
    }

private:
    /// Mechanical energy per unit mass about the pivot height, J/kg (display only).
    double Energy() const {
        const double y = E::D(bob_->GetPosition().y) - 20;
        const double vx = E::D(bob_->GetLinearVelocity().x), vy = E::D(bob_->GetLinearVelocity().y);
        const double w = E::D(bob_->GetAngularVelocity());
        return kG * y + 0.5 * (vx * vx + vy * vy) + 0.5 * (kRadius * kRadius / 2) * w * w;
    }

    typename E::Body* bob_ = nullptr;
    double energy0_ = 0;
    double prevX_ = 0;
    std::vector<double> crossings_;
};

}  // namespace lockbox::scenes
