#pragma once
/// joint_grid (SCENES.md): Box2D v3 joint_grid, N = 100. For k = 0..99 (columns), i = 0..99
/// (rows) a body at (k, -i): static if 47 <= k <= 53 and i = 0, else dynamic; circle radius
/// 0.4, density 1, friction 0.6, filter category 0x0002, mask 0xFFFD (no contacts at all).
/// Revolute joints (no limit, no motor): if i > 0 to the body above (localAnchorA (0, -0.5),
/// localAnchorB (0, 0.5)); if k > 0 to the body on the left (localAnchorA (0.5, 0),
/// localAnchorB (-0.5, 0)). 19800 joints. Sleep off; 500 steps, 8/3, 60 Hz.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A hanging grid of bodies held by revolute joints only.
template <class E>
class JointGridScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "joint_grid", 500, 8, 3, 60, false, true, true, "v3 joint_grid: 10000 bodies, 19800 revolute joints"};
    /// True when engine E has the joint types this scene needs.
    static constexpr bool kAvailable = E::kHasRevolute;
    /// n: grid side (100 in SCENES.md; smaller grids for quick tests; static columns are
    /// those with |k - n/2 + 3| <= 3, i.e. 47..53 for n = 100).
    explicit JointGridScene(int n = 100) : n_(n) {}
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        if constexpr (kAvailable) {
            typename E::CircleShape circle;
            circle.m_radius = E::R(4, 10);
            typename E::FixtureDef fd;
            fd.shape = &circle;
            fd.density = 1;
            fd.friction = E::R(6, 10);
            fd.filter.categoryBits = 0x0002;
            fd.filter.maskBits = 0xFFFD;
            const int lo = n_ / 2 - 3, hi = n_ / 2 + 3;
            std::vector<typename E::Body*> bodies(static_cast<size_t>(n_) * n_, nullptr);
            for (int k = 0; k < n_; ++k) {
                for (int i = 0; i < n_; ++i) {
                    typename E::BodyDef bd;
                    bd.type = (k >= lo && k <= hi && i == 0) ? E::kStatic : E::kDynamic;
                    bd.position = E::V(k, -i);
                    auto* body = e.world().CreateBody(&bd);
                    body->CreateFixture(&fd);
                    const size_t index = static_cast<size_t>(k) * n_ + i;
                    bodies[index] = body;
                    if (i > 0) {
                        typename E::RevoluteJointDef jd;
                        jd.bodyA = bodies[index - 1];
                        jd.bodyB = body;
                        jd.localAnchorA = E::V(0, E::R(-1, 2));
                        jd.localAnchorB = E::V(0, E::R(1, 2));
                        e.CreateJoint(jd);
                    }
                    if (k > 0) {
                        typename E::RevoluteJointDef jd;
                        jd.bodyA = bodies[index - n_];
                        jd.bodyB = body;
                        jd.localAnchorA = E::V(E::R(1, 2), 0);
                        jd.localAnchorB = E::V(E::R(-1, 2), 0);
                        e.CreateJoint(jd);
                    }
                }
            }
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
    int n_;
    double jointSep_ = 0;
};

}  // namespace lockbox::scenes
