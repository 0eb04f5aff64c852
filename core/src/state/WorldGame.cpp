#include "lockbox/state/WorldGame.h"

#include "lockbox/dynamics/World.h"

namespace lockbox {

void AdvanceWorldFrame(b2World& world, WorldGame& game, int32 frame, std::span<const uint8> inputs,
                       const WorldStepSettings& step) {
    game.Apply(world, frame, inputs);
    // 1/tickRate seconds rounded once to Q16.16: the time step the replay header records.
    world.Step(Fixed::FromRatio(1, step.tickRate == 0 ? 1 : step.tickRate), static_cast<int32>(step.velocityIterations),
               static_cast<int32>(step.positionIterations));
}

}  // namespace lockbox
