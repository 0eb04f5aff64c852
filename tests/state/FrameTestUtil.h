#pragma once
// Helpers shared by the rollback-frame tests: a box to spawn, a body to change, and a saved
// frame with the hashes of the frames after it, to check a restore against.

#include <vector>

#include "StateTestUtil.h"

namespace lockbox::testing_state {

/// Hash after each of `frames` further frames of a run.
inline std::vector<uint64> Future(SceneRun& run, int frames) {
    std::vector<uint64> out;
    for (int i = 0; i < frames; ++i) {
        run.Advance();
        out.push_back(run.world().Hash());
    }
    return out;
}

/// A dynamic quarter-metre box with one fixture of density 1.
inline b2Body* AddBox(b2World& world, b2Vec2 at) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position = at;
    b2Body* body = world.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(Fixed(1) / 4, Fixed(1) / 4);
    body->CreateFixture(&box, 1);
    return body;
}

/// The first dynamic body of the body list (the newest), or nullptr.
inline b2Body* FirstDynamic(b2World& world) {
    for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() == b2_dynamicBody) return b;
    }
    return nullptr;
}

/// A frame saved from a run, with its hash, its frame number and the hashes of the
/// `futureFrames` frames after it (the run is left after those frames).
struct SavedFrame {
    b2WorldFrame frame;
    uint64 hash = 0;
    int step = 0;
    std::vector<uint64> future;

    SavedFrame(SceneRun& run, int futureFrames) {
        run.world().SaveFrame(frame);
        hash = run.world().Hash();
        step = run.step;
        future = Future(run, futureFrames);
    }

    /// After a restore of `frame`: the state and its future are the saved ones.
    void ExpectBack(SceneRun& run, const char* what = "") const {
        EXPECT_EQ(run.world().Hash(), hash) << what;
        run.step = step;
        EXPECT_EQ(Future(run, static_cast<int>(future.size())), future) << what;
    }
};

}  // namespace lockbox::testing_state
