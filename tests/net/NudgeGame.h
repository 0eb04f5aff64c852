#pragma once
// A forced divergence for the net tests (lockstep and rollback): a SceneGame whose world is
// nudged at one frame. Every time that frame is applied (rollbacks included), the first dynamic
// body first moves by 1/65536 m, so the divergence survives re-simulation.

#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox/state/WorldGame.h"

namespace lockbox::net::test_games {

class NudgeGame : public WorldGame {
public:
    explicit NudgeGame(replay::SceneGame& inner) : m_inner(inner) {}
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        if (frame == nudgeFrame) {
            for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
                if (b->GetType() != b2_dynamicBody) continue;
                b2Vec2 p = b->GetPosition();
                p.x = p.x + Fixed::FromRaw(1);
                b->SetTransform(p, b->GetAngle());
                break;
            }
        }
        m_inner.Apply(world, frame, inputs);
    }
    void SaveUserState(std::vector<uint8>& out) const override { m_inner.SaveUserState(out); }
    void LoadUserState(std::span<const uint8> in) override { m_inner.LoadUserState(in); }
    int32_t nudgeFrame = -1;  ///< the frame whose Apply nudges first (-1: never)

private:
    replay::SceneGame& m_inner;
};

}  // namespace lockbox::net::test_games
