#pragma once
// The fencepost observer shared by the recorder and the player (private): hashes the world at
// every step stage into a kStagesPerFrame array, and every island's solver buffers after its
// velocity and its position phase into kSolvePhasesPerFrame running hashes, after an optional
// StageHook has seen each point.

#ifndef XXH_STATIC_LINKING_ONLY
#define XXH_STATIC_LINKING_ONLY
#endif
#include <xxhash.h>

#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/replay/Format.h"
#include "lockbox/replay/Game.h"

namespace lockbox::replay::detail {

class StageHasher : public b2StepObserver {
public:
    StageHasher() noexcept {
        for (XXH3_state_t& s : m_phaseState) XXH3_64bits_reset(&s);
    }

    /// Starts a frame: clears the stages and records stage 0 (inputs applied).
    void BeginFrame(int32 frame, b2World& world) {
        m_frame = frame;
        m_world = &world;
        for (uint64& h : stages) h = 0;
        for (uint64& h : solve) h = 0;
        for (XXH3_state_t& s : m_phaseState) XXH3_64bits_reset(&s);
        if (hook != nullptr) hook->OnStage(frame, 0, world);
        if (hashing) stages[0] = world.Hash();
    }
    void OnStage(b2StepStage stage, const b2World& world) override {
        (void)world;
        const uint32 index = static_cast<uint32>(stage) + 1;
        if (index >= kStagesPerFrame) return;
        // The hook gets the mutable world the player owns (the observer interface is const).
        if (hook != nullptr) hook->OnStage(m_frame, index, *m_world);
        if (hashing) stages[index] = m_world->Hash();
        if (hashing && stage == b2StepStage::e_solve)
            for (uint32 p = 0; p < kSolvePhasesPerFrame; ++p) solve[p] = XXH3_64bits_digest(&m_phaseState[p]);
    }
    void OnIsland(b2IslandPhase phase, std::span<b2Body* const> bodies, std::span<b2Position> positions,
                  std::span<b2Velocity> velocities) override {
        const uint32 p = static_cast<uint32>(phase);
        if (p >= kSolvePhasesPerFrame) return;
        if (hook != nullptr) hook->OnIsland(m_frame, phase, bodies, positions, velocities);
        if (!hashing) return;
        // Little-endian words: the body id, then x, y, angle (raw Q16.16) of the phase's buffer.
        for (size_t i = 0; i < bodies.size(); ++i) {
            const bool vel = phase == b2IslandPhase::e_velocity;
            const uint32 words[4] = {static_cast<uint32>(bodies[i]->GetId()),
                                     static_cast<uint32>(vel ? velocities[i].v.x.Raw() : positions[i].c.x.Raw()),
                                     static_cast<uint32>(vel ? velocities[i].v.y.Raw() : positions[i].c.y.Raw()),
                                     static_cast<uint32>(vel ? velocities[i].w.Raw() : positions[i].a.Raw())};
            uint8 bytes[16];
            for (int w = 0; w < 4; ++w)
                for (int b = 0; b < 4; ++b) bytes[w * 4 + b] = static_cast<uint8>(words[w] >> (8 * b));
            XXH3_64bits_update(&m_phaseState[p], bytes, sizeof bytes);
        }
    }

    StageHook* hook = nullptr;
    bool hashing = true;
    uint64 stages[kStagesPerFrame] = {};
    uint64 solve[kSolvePhasesPerFrame] = {};

private:
    int32 m_frame = 0;
    b2World* m_world = nullptr;
    XXH3_state_t m_phaseState[kSolvePhasesPerFrame];
};

}  // namespace lockbox::replay::detail
