#pragma once
/// many_pyramids (SCENES.md): Box2D v3 many_pyramids. 20 rows x 20 columns of pyramids of
/// base 10 (55 boxes each, 22000 boxes). 20 edges from x = -110 to 110 at y = 11 r on one
/// static body; pyramid (r, c) has baseY = 11 r, centerX = -110 + 11 c + 1, boxes at
/// x = centerX - 0.5 + (i+1) 0.5 + (j-i) 1.0, y = baseY + (2i+1) 0.5, 0.5x0.5 half extents,
/// density 1, friction 0.6. Sleep off. 200 steps, 8/3, 60 Hz. Tracks the 400 apexes.

#include "lockbox/scenes/Scene.h"

namespace lockbox::scenes {

/// A grid of small touching pyramids (20x20 in SCENES.md; smaller grids for quick tests).
template <class E>
class ManyPyramidsScene : public Scene<E> {
public:
    /// Name, default steps, iterations, Hz and sleep flag of this scene.
    static constexpr SceneInfo kInfo{
        "many_pyramids", 200, 8, 3, 60, false, true, true, "v3 many_pyramids: 400 pyramids, 22000 boxes, sleep off"};
    static constexpr int kBase = 10;
    /// rows, columns: grid size (1..20 each).
    explicit ManyPyramidsScene(int rows = 20, int columns = 20) : rows_(rows), columns_(columns) {}
    /// The defaults above.
    const SceneInfo& Info() const override { return kInfo; }

    void Build(E& e) override {
        typename E::BodyDef groundDef;
        auto* ground = e.world().CreateBody(&groundDef);
        typename E::EdgeShape edge;
        for (int r = 0; r < rows_; ++r) {
            E::SetEdge(edge, E::V(-110, 11 * r), E::V(110, 11 * r));
            ground->CreateFixture(&edge, 0);
        }
        typename E::PolygonShape box;
        box.SetAsBox(E::R(1, 2), E::R(1, 2));
        typename E::FixtureDef fd;
        fd.shape = &box;
        fd.density = 1;
        fd.friction = E::R(6, 10);
        for (int r = 0; r < rows_; ++r) {
            for (int c = 0; c < columns_; ++c) {
                const int baseY = 11 * r;
                const int centerX = -110 + 11 * c + 1;
                typename E::Body* apex = nullptr;
                for (int i = 0; i < kBase; ++i) {
                    for (int j = i; j < kBase; ++j) {
                        typename E::BodyDef bd;
                        bd.type = E::kDynamic;
                        // In half metres: x = 2 centerX - 1 + (i+1) + 2(j-i), y = 2 baseY + 2i + 1.
                        bd.position =
                            E::V(E::R(2 * centerX - 1 + (i + 1) + 2 * (j - i), 2), E::R(2 * baseY + 2 * i + 1, 2));
                        apex = e.world().CreateBody(&bd);
                        apex->CreateFixture(&fd);
                    }
                }
                apexes_.push_back(apex);
                restY_.push_back(baseY + kBase - 0.5);
                x0_.push_back(E::D(apex->GetPosition().x));
            }
        }
    }

    void Report(E& e, std::vector<Metric>& out) override {
        Scene<E>::Report(e, out);
        double maxDx = 0, maxSag = 0;
        int collapsed = 0;
        for (size_t k = 0; k < apexes_.size(); ++k) {
            const double dx = E::D(apexes_[k]->GetPosition().x) - x0_[k];
            const double sag = restY_[k] - E::D(apexes_[k]->GetPosition().y);
            maxDx = std::max(maxDx, std::fabs(dx));
            maxSag = std::max(maxSag, sag);
            if (std::fabs(dx) > 0.5 || sag > 0.5) ++collapsed;
        }
        out.push_back({"top_dx", maxDx});
        out.push_back({"top_sag", maxSag});
        out.push_back({"collapsed", static_cast<double>(collapsed)});
    }

private:
    int rows_, columns_;
    std::vector<typename E::Body*> apexes_;
    std::vector<double> restY_, x0_;
};

}  // namespace lockbox::scenes
