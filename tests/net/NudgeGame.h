#pragma once
// A forced divergence for the net tests (lockstep and rollback): a SceneGame whose world is
// nudged at one frame. Every time that frame is applied (rollbacks included), the first dynamic
// body first moves by 1/65536 m, so the divergence survives re-simulation.

#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/replay/Game.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net::test_games {

class NudgeGame : public replay::Game {
public:
    explicit NudgeGame(replay::SceneGame& inner) : inner_(inner) {}
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
        inner_.Apply(world, frame, inputs);
    }
    void SaveUserState(std::vector<uint8>& out) const override { inner_.SaveUserState(out); }
    void LoadUserState(std::span<const uint8> in) override { inner_.LoadUserState(in); }
    int32_t nudgeFrame = -1;  ///< the frame whose Apply nudges first (-1: never)

private:
    replay::SceneGame& inner_;
};

}  // namespace lockbox::net::test_games
