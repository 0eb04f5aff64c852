#pragma once
// A test game for RollbackSession without a world: its state is one integer into which each
// Advance mixes the inputs and the frame. It runs a request list the way a real game must
// (save, load, advance in order), keeps every saved state and the inputs of each frame's
// latest Advance (a rollback's re-simulation replaces them), and can inject a fault.

#include <cstdint>
#include <map>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackSession.h"

namespace lockbox::net {

struct MixGame {
    uint64_t state = 0x1234;
    std::map<int32_t, uint64_t> saved;
    std::map<int32_t, std::vector<uint8_t>> inputs;  ///< per frame, the latest Advance's inputs
    int32_t loads = 0, advances = 0;
    uint64_t corruptAt = UINT64_MAX;  ///< frame whose Advance adds a fault

    void Run(RollbackSession& s, const std::vector<RollbackRequest>& reqs) {
        for (const auto& r : reqs) {
            if (const auto* sv = std::get_if<SaveState>(&r)) {
                saved[sv->frame] = state;
                if (sv->wantHash) s.ReportHash(sv->frame, state);
            } else if (const auto* ld = std::get_if<LoadState>(&r)) {
                ASSERT_TRUE(saved.count(ld->frame)) << "load of a frame never saved: " << ld->frame;
                state = saved[ld->frame];
                ++loads;
            } else if (const auto* a = std::get_if<AdvanceRequest>(&r)) {
                for (uint8_t b : a->inputs) state = (state ^ b) * 0x100000001B3ull;
                state += static_cast<uint64_t>(a->frame);
                if (static_cast<uint64_t>(a->frame) == corruptAt) state ^= 1;
                inputs[a->frame] = a->inputs;
                ++advances;
            }
        }
    }
};

}  // namespace lockbox::net
