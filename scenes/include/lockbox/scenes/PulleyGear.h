#pragma once
/// pulley_gear (lockbox's own): a machine of pulley, gear and rack joints over a ground edge
/// (-20,0)-(20,0).
/// - Pulley: boxes 0.5x0.5 at (-4, 10) (density 2) and (-1, 10) (density 1) hang from ground
///   anchors (-4, 20) and (-1, 20) with ratio 1.5 (lengthA + 1.5 lengthB = constant); box A
///   is heavier than 1.5 B, so it sinks and lands on the ground.
/// - Gear train: disc 1 (radius 1) at (4, 5) and disc 2 (radius 2) at (8, 5) turn on revolute
///   joints to the ground; a gear joint (ratio 2) couples them; disc 1's motor runs at 2 rad/s
///   with at most 50 N m.
/// - Rack: a 3x0.25 box at (8, 2.5) on a prismatic joint (axis (1, 0), limits +-5 m) geared to
///   disc 2 (ratio -0.5: the rack moves 2 m per radian), so the train jams at the limit.
/// Discs and rack share filter group -1 (they mesh through the gears, not through contacts).
/// 600 steps, 8/3, 60 Hz. Reports pulley_err and gear_err (drift of the joints' constraints).

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// Pulley, gear and rack-and-pinion joints in one scene.
template <class E>
class PulleyGearScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "pulley_gear", 600, 8, 3, 60, true, false, false, "pulley, gear train and rack-and-pinion machine"};
    /// True when engine E has the joint types this scene needs.
    static constexpr bool kAvailable = E::kHasRevolute && E::kHasPrismatic && E::kHasPulley && E::kHasGear;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        if constexpr (kAvailable) {
            typename E::BodyDef groundDef;
            ground_ = e.world().CreateBody(&groundDef);
            typename E::EdgeShape edge;
            E::SetEdge(edge, E::V(-20, 0), E::V(20, 0));
            ground_->CreateFixture(&edge, 0);

            // Pulley.
            typename E::PolygonShape box;
            box.SetAsBox(E::R(1, 2), E::R(1, 2));
            const int xs[2] = {-4, -1};
            const int densities[2] = {2, 1};
            for (int k = 0; k < 2; ++k) {
                typename E::BodyDef bd;
                bd.type = E::kDynamic;
                bd.position = E::V(xs[k], 10);
                pulleyBodies_[k] = e.world().CreateBody(&bd);
                pulleyBodies_[k]->CreateFixture(&box, densities[k]);
            }
            typename E::PulleyJointDef pd;
            pd.Initialize(pulleyBodies_[0], pulleyBodies_[1], E::V(-4, 20), E::V(-1, 20), E::V(-4, E::R(21, 2)),
                          E::V(-1, E::R(21, 2)), E::R(3, 2));
            e.CreateJoint(pd);
            pulley0_ = PulleyCoordinate();

            // Gear train.
            typename E::FixtureDef fd;
            fd.density = 1;
            fd.friction = E::R(6, 10);
            fd.filter.groupIndex = -1;
            typename E::CircleShape disc;
            typename E::Joint* revolutes[2];
            const int cx[2] = {4, 8};
            const int radii[2] = {1, 2};
            for (int k = 0; k < 2; ++k) {
                typename E::BodyDef bd;
                bd.type = E::kDynamic;
                bd.position = E::V(cx[k], 5);
                discs_[k] = e.world().CreateBody(&bd);
                disc.m_radius = radii[k];
                fd.shape = &disc;
                discs_[k]->CreateFixture(&fd);
                typename E::RevoluteJointDef rd;
                rd.Initialize(ground_, discs_[k], E::V(cx[k], 5));
                rd.enableMotor = k == 0;
                rd.motorSpeed = 2;
                E::SetMaxMotorTorque(rd, k == 0 ? 50 : 0);
                revolutes[k] = e.CreateJoint(rd);
            }
            typename E::GearJointDef gd;
            gd.bodyA = discs_[0];
            gd.bodyB = discs_[1];
            gd.joint1 = revolutes[0];
            gd.joint2 = revolutes[1];
            gd.ratio = 2;
            e.CreateJoint(gd);

            // Rack.
            typename E::BodyDef rb;
            rb.type = E::kDynamic;
            rb.position = E::V(8, E::R(5, 2));
            rack_ = e.world().CreateBody(&rb);
            typename E::PolygonShape rackShape;
            rackShape.SetAsBox(3, E::R(1, 4));
            fd.shape = &rackShape;
            rack_->CreateFixture(&fd);
            typename E::PrismaticJointDef prd;
            prd.Initialize(ground_, rack_, E::V(8, E::R(5, 2)), E::V(1, 0));
            prd.enableLimit = true;
            prd.lowerTranslation = -5;
            prd.upperTranslation = 5;
            auto* prismatic = e.CreateJoint(prd);
            typename E::GearJointDef gd2;
            gd2.bodyA = discs_[1];
            gd2.bodyB = rack_;
            gd2.joint1 = revolutes[1];
            gd2.joint2 = prismatic;
            gd2.ratio = E::R(-1, 2);
            e.CreateJoint(gd2);
        }
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        if (!rack_) return;
        pulleyErr_ = std::max(pulleyErr_, std::fabs(PulleyCoordinate() - pulley0_));
        const double a1 = Unwrap(0, E::D(discs_[0]->GetAngle()));
        const double a2 = Unwrap(1, E::D(discs_[1]->GetAngle()));
        const double t = E::D(rack_->GetPosition().x) - 8;
        gearErr_ = std::max(gearErr_, std::fabs(a1 + 2 * a2));
        gearErr_ = std::max(gearErr_, std::fabs(a2 - 0.5 * t));
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        out.push_back({"pulley_err", pulleyErr_});
        out.push_back({"gear_err", gearErr_});
        if (rack_) out.push_back({"rack_x", E::D(rack_->GetPosition().x)});
    }

private:
    /// Continuous angle of disc k: lockbox keeps body angles in [-pi, pi), float Box2D does
    /// not; adding each step's change reduced to [-pi, pi) gives both the same unwrapped angle
    /// (the discs turn far less than pi per step).
    double Unwrap(int k, double angle) {
        const double pi = 3.14159265358979323846;
        double d = angle - lastAngle_[k];
        d -= 2 * pi * std::floor((d + pi) / (2 * pi));
        lastAngle_[k] = angle;
        unwrapped_[k] += d;
        return unwrapped_[k];
    }

    /// lengthA + 1.5 lengthB from the bodies' top-centre anchors, m.
    double PulleyCoordinate() const {
        const double ya = E::D(pulleyBodies_[0]->GetPosition().y) + 0.5;
        const double yb = E::D(pulleyBodies_[1]->GetPosition().y) + 0.5;
        const double xa = E::D(pulleyBodies_[0]->GetPosition().x) + 4;
        const double xb = E::D(pulleyBodies_[1]->GetPosition().x) + 1;
        return std::sqrt(xa * xa + (20 - ya) * (20 - ya)) + 1.5 * std::sqrt(xb * xb + (20 - yb) * (20 - yb));
    }

    typename E::Body* ground_ = nullptr;
    typename E::Body* pulleyBodies_[2] = {nullptr, nullptr};
    typename E::Body* discs_[2] = {nullptr, nullptr};
    typename E::Body* rack_ = nullptr;
    double pulley0_ = 0, pulleyErr_ = 0, gearErr_ = 0;
    double lastAngle_[2] = {0, 0}, unwrapped_[2] = {0, 0};
};

}  // namespace lockbox::scenes
