#pragma once
// Helpers shared by the world-state tests: build a library scene, step it, and compare two
// worlds field by field through their hash reports.

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::testing_state {

/// A built scene with its engine adapter.
struct SceneRun {
    std::unique_ptr<scenes::LockboxScene> scene;
    std::unique_ptr<scenes::LockboxEngine> engine;
    int step = 0;

    /// build = false leaves the world empty (a late joiner restores into it).
    explicit SceneRun(std::string_view name, bool build = true) : scene(scenes::MakeLockboxScene(name)) {
        if (!scene) return;
        engine = std::make_unique<scenes::LockboxEngine>();
        scenes::ConfigureWorld(*engine, scene->Info(), scenes::RunSettings{});
        scene->Prepare(scenes::Resolve(scene->Info(), scenes::RunSettings{}));
        if (build) scene->Build(*engine);
    }
    b2World& world() { return engine->world(); }
    /// One frame as the scene defines it (its pre-step action, then Step).
    void Advance() {
        const auto& info = scene->Info();
        scene->BeforeStep(*engine, step);
        engine->Step(info.hz, info.velocityIterations, info.positionIterations);
        ++step;
    }
    void Advance(int n) {
        for (int i = 0; i < n; ++i) Advance();
    }
};

/// [begin, end) of snapshot section `tag`'s contents, found by walking the section headers
/// (tag and length, little-endian) after the 33-byte header; {0, 0} when it is absent.
inline std::pair<size_t, size_t> SectionBytes(const std::vector<uint8>& image, uint32 tag) {
    auto le32 = [&](size_t at) {
        return uint32{image[at]} | uint32{image[at + 1]} << 8 | uint32{image[at + 2]} << 16 |
               uint32{image[at + 3]} << 24;
    };
    size_t at = 33;
    while (at + 8 <= image.size()) {
        const uint32 t = le32(at), length = le32(at + 4);
        if (t == tag) return {at + 8, at + 8 + length};
        at += 8 + length;
    }
    return {0, 0};
}

/// Names the first category and body where two worlds differ ("" when equal).
inline std::string DescribeDifference(const b2World& a, const b2World& b) {
    const b2WorldHashReport ra = b2WorldHashDetailed(a);
    const b2WorldHashReport rb = b2WorldHashDetailed(b);
    if (ra.total == rb.total) return "";
    const b2HashMismatch m = b2CompareHashReports(ra, rb);
    return "category " + std::string(b2HashCategoryName(m.category)) + ", body " + std::to_string(m.bodyId);
}

}  // namespace lockbox::testing_state

namespace lockbox::testing_state {

/// The invariant snapshots rely on (StateWalk.h): every body's contact edges are in world
/// contact-list order, and its joint edges in world joint-list order.
inline ::testing::AssertionResult EdgesFollowWorldLists(b2World& world) {
    for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        const b2ContactEdge* e = b->GetContactList();
        for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) {
            if (c->GetFixtureA()->GetBody() != b && c->GetFixtureB()->GetBody() != b) continue;
            if (e == nullptr || e->contact != c)
                return ::testing::AssertionFailure() << "body " << b->GetId() << ": contact edges out of list order";
            e = e->next;
        }
        if (e != nullptr) return ::testing::AssertionFailure() << "body " << b->GetId() << ": extra contact edges";
        const b2JointEdge* je = b->GetJointList();
        for (b2Joint* j = world.GetJointList(); j; j = j->GetNext()) {
            // CreateJoint links edge A then edge B at the head: B comes first when both sides
            // are on this body (a gear joint may do that).
            for (int side = 1; side >= 0; --side) {
                if ((side == 0 ? j->GetBodyA() : j->GetBodyB()) != b) continue;
                if (je == nullptr || je->joint != j)
                    return ::testing::AssertionFailure() << "body " << b->GetId() << ": joint edges out of list order";
                je = je->next;
            }
        }
        if (je != nullptr) return ::testing::AssertionFailure() << "body " << b->GetId() << ": extra joint edges";
    }
    return ::testing::AssertionSuccess();
}

}  // namespace lockbox::testing_state
