#pragma once
// The fencepost observer shared by the recorder and the player (private): hashes the world at
// every step stage into a kStagesPerFrame array, after an optional StageHook has seen it.

#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/replay/Format.h"
#include "lockbox/replay/Game.h"

namespace lockbox::replay::detail {

class StageHasher : public b2StepObserver {
public:
    /// Starts a frame: clears the stages and records stage 0 (inputs applied).
    void BeginFrame(int32 frame, b2World& world) {
        frame_ = frame;
        world_ = &world;
        for (uint64& h : stages) h = 0;
        if (hook != nullptr) hook->OnStage(frame, 0, world);
        if (hashing) stages[0] = world.Hash();
    }
    void OnStage(b2StepStage stage, const b2World& world) override {
        (void)world;
        const uint32 index = static_cast<uint32>(stage) + 1;
        if (index >= kStagesPerFrame) return;
        // The hook gets the mutable world the player owns (the observer interface is const).
        if (hook != nullptr) hook->OnStage(frame_, index, *world_);
        if (hashing) stages[index] = world_->Hash();
    }

    StageHook* hook = nullptr;
    bool hashing = true;
    uint64 stages[kStagesPerFrame] = {};

private:
    int32 frame_ = 0;
    b2World* world_ = nullptr;
};

}  // namespace lockbox::replay::detail
