#pragma once
/// ragdolls (lockbox's own): a pile of 12 ten-part ragdolls (head circle, torso, upper and
/// lower arms, thighs, shins) joined by nine limited revolute joints each, dropped into a
/// container of edges (-10,0)-(10,0), (-10,0)-(-10,30), (10,0)-(10,30). Ragdoll k stands at
/// x = -6 + 4 (k % 4), feet at y = 1 + 3.5 (k / 4); its parts share filter group -(k + 1), so a
/// ragdoll never collides with itself. Density 1, friction 0.6. 600 steps, 8/3, 60 Hz.
/// Reports joint_sep (limits and contacts fight the joints here) and max_pen.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A pile of jointed ragdolls.
template <class E>
class RagdollsScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "ragdolls", 600, 8, 3, 60, true, false, false, "12 ragdolls with limited revolute joints piled in a box"};
    /// True when engine E has the joint types this scene needs.
    static constexpr bool kAvailable = E::kHasRevolute;
    static constexpr int kCount = 12;
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        if constexpr (kAvailable) {
            typename E::BodyDef groundDef;
            auto* ground = e.world().CreateBody(&groundDef);
            typename E::EdgeShape edge;
            E::SetEdge(edge, E::V(-10, 0), E::V(10, 0));
            ground->CreateFixture(&edge, 0);
            E::SetEdge(edge, E::V(-10, 0), E::V(-10, 30));
            ground->CreateFixture(&edge, 0);
            E::SetEdge(edge, E::V(10, 0), E::V(10, 30));
            ground->CreateFixture(&edge, 0);
            for (int k = 0; k < kCount; ++k) BuildOne(e, k);
        }
    }

    void AfterStep(E& e, int step) override {
        Scene<E>::AfterStep(e, step);
        jointSep_ = std::max(jointSep_, MaxJointSeparation(e));
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        out.push_back({"joint_sep", std::max(jointSep_, MaxJointSeparation(e))});
    }

private:
    /// Part layout in centimetres relative to the feet: centre x, y, half width, half height
    /// (half height 0 marks the circular head, radius = half width).
    struct Part {
        int x, y, hw, hh;
    };

    void BuildOne(E& e, int k) {
        if constexpr (kAvailable) {
            static constexpr Part kParts[10] = {
                {0, 150, 25, 60},                       // 0 torso (90..210)
                {0, 230, 20, 0},                        // 1 head
                {-35, 180, 10, 30}, {35, 180, 10, 30},  // 2, 3 upper arms (150..210)
                {-35, 120, 10, 30}, {35, 120, 10, 30},  // 4, 5 lower arms (90..150)
                {-12, 65, 10, 25},  {12, 65, 10, 25},   // 6, 7 thighs (40..90)
                {-12, 20, 10, 20},  {12, 20, 10, 20},   // 8, 9 shins (0..40)
            };
            // Joint: parent, child, anchor (cm), lower and upper angle (deg).
            struct JointSpec {
                int a, b, x, y, lo, hi;
            };
            static constexpr JointSpec kJoints[9] = {
                {0, 1, 0, 210, -40, 40},                              // neck
                {0, 2, -35, 205, -90, 90}, {0, 3, 35, 205, -90, 90},  // shoulders
                {2, 4, -35, 150, 0, 130},  {3, 5, 35, 150, -130, 0},  // elbows
                {0, 6, -12, 90, -30, 90},  {0, 7, 12, 90, -30, 90},   // hips
                {6, 8, -12, 40, -120, 0},  {7, 9, 12, 40, -120, 0},   // knees
            };
            const int baseX = 100 * (-6 + 4 * (k % 4));
            const int baseY = 100 + 350 * (k / 4);
            typename E::Body* bodies[10];
            for (int p = 0; p < 10; ++p) {
                const Part& part = kParts[p];
                typename E::BodyDef bd;
                bd.type = E::kDynamic;
                bd.position = E::V(E::R(baseX + part.x, 100), E::R(baseY + part.y, 100));
                bodies[p] = e.world().CreateBody(&bd);
                typename E::FixtureDef fd;
                fd.density = 1;
                fd.friction = E::R(6, 10);
                fd.filter.groupIndex = static_cast<int16_t>(-(k + 1));
                typename E::CircleShape circle;
                typename E::PolygonShape box;
                if (part.hh == 0) {
                    circle.m_radius = E::R(part.hw, 100);
                    fd.shape = &circle;
                } else {
                    box.SetAsBox(E::R(part.hw, 100), E::R(part.hh, 100));
                    fd.shape = &box;
                }
                bodies[p]->CreateFixture(&fd);
            }
            for (const JointSpec& j : kJoints) {
                typename E::RevoluteJointDef jd;
                jd.Initialize(bodies[j.a], bodies[j.b], E::V(E::R(baseX + j.x, 100), E::R(baseY + j.y, 100)));
                jd.enableLimit = true;
                jd.lowerAngle = E::Deg(j.lo);
                jd.upperAngle = E::Deg(j.hi);
                e.CreateJoint(jd);
            }
        }
    }

    double jointSep_ = 0;
};

}  // namespace lockbox::scenes
