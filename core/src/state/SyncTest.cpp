// lockbox::SyncTest (SyncTest.h): save every frame into a ring, roll back k frames after each
// one, re-simulate, compare hashes; optionally mispredict first.

#include "lockbox/state/SyncTest.h"

#include <utility>

#include "FastXxh3.h"
#include "dynamics/WorldState.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/joints/DistanceJoint.h"

namespace lockbox {

namespace {

/// splitmix64: a tiny, well-mixed integer generator (the same sequence everywhere).
uint64 NextRandom(uint64& state) {
    state += 0x9E3779B97F4A7C15ULL;
    uint64 z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/// A uniform Fixed in [-limit, limit] (limit in whole units).
Fixed RandomFixed(uint64& state, int32 limit) {
    const uint64 span = 2 * static_cast<uint64>(limit) * 65536 + 1;
    return Fixed::FromRaw(static_cast<int32>(static_cast<int64_t>(NextRandom(state) % span) - int64_t{limit} * 65536));
}

}  // namespace

SyncTest::SyncTest(b2World& world, WorldGame& game, SyncTestInputSource inputs, SyncTestConfig config)
    : m_world(world), m_game(game), m_source(std::move(inputs)), m_config(config) {
    if (m_config.checkDistance < 1) m_config.checkDistance = 1;
    if (m_config.stride < 1) m_config.stride = 1;
    const size_t ring = static_cast<size_t>(m_config.checkDistance) + 1;
    m_images.resize(ring);
    m_user.resize(ring);
    if (m_config.frames) m_frames.resize(ring);
}

std::span<const uint8> SyncTest::InputsFor(int32 frame) {
    const size_t f = static_cast<size_t>(frame < 0 ? 0 : frame);
    while (m_inputs.size() <= f) {
        std::vector<uint8> in(m_config.inputBytes, 0);
        if (m_source && !in.empty()) m_source(static_cast<int32>(m_inputs.size()), in);
        m_inputs.push_back(std::move(in));
    }
    return m_inputs[f];
}

void SyncTest::Advance(int32 frame) { AdvanceWorldFrame(m_world, m_game, frame, InputsFor(frame), m_config.step); }

uint64 SyncTest::StateHash() {
    m_scratch.clear();
    m_game.SaveUserState(m_scratch);
    const uint64 parts[2] = {m_world.Hash(), state_detail::Xxh3(m_scratch.data(), m_scratch.size())};
    return state_detail::Xxh3(parts, sizeof parts);
}

uint64 SyncTest::SaveFrame(int32 frame) {
    const size_t slot = static_cast<size_t>(frame) % m_images.size();
    m_world.Save(m_images[slot]);
    if (m_config.frames) m_world.SaveFrame(m_frames[slot]);
    m_user[slot].clear();
    m_game.SaveUserState(m_user[slot]);
    // The frame's hash read from the image just written: the value StateHash() gives, at a
    // fraction of a walk's cost. Re-simulated frames are hashed by walking the world
    // (CheckFrame), so every comparison also checks the two paths against each other.
    const b2SnapshotHashResult image = b2SnapshotHash(m_images[slot]);
    if (!image.ok()) return StateHash();
    const uint64 parts[2] = {image.total, state_detail::Xxh3(m_user[slot].data(), m_user[slot].size())};
    return state_detail::Xxh3(parts, sizeof parts);
}

bool SyncTest::LoadFrame(int32 frame, SyncTestResult& result) {
    const size_t slot = static_cast<size_t>(frame) % m_images.size();
    const b2RestoreResult restored =
        m_config.frames ? m_world.RestoreFrame(m_frames[slot]) : m_world.Restore(m_images[slot]);
    if (!restored.ok()) {
        result.ok = false;
        result.firstBadFrame = frame;
        result.message = "restoring frame " + std::to_string(frame) + " failed: " + restored.message;
        return false;
    }
    m_game.LoadUserState(m_user[slot]);
    return CheckFrame(frame, result);
}

bool SyncTest::CheckFrame(int32 frame, SyncTestResult& result) {
    const uint64 actual = StateHash();
    const uint64 expected = m_hashes[static_cast<size_t>(frame)];
    if (actual == expected) return true;
    result.ok = false;
    result.firstBadFrame = frame;
    result.expected = expected;
    result.actual = actual;
    // The first run's state at this frame is still in the ring: compare category by category.
    b2World reference(b2Vec2(0, 0));
    const size_t slot = static_cast<size_t>(frame) % m_images.size();
    if (reference.Restore(m_images[slot]).ok()) {
        result.where = b2CompareHashReports(b2WorldHashDetailed(reference), b2WorldHashDetailed(m_world));
    }
    const bool worldDiffers = result.where.category != b2HashCategory::e_count;
    result.message = "state after frame " + std::to_string(frame) + " differs on re-simulation: " +
                     (worldDiffers ? "category " + std::string(b2HashCategoryName(result.where.category)) + ", body " +
                                         std::to_string(result.where.bodyId)
                                   : std::string("user state"));
    return false;
}

void SyncTest::WrongInputs(int32 frame, bool spawnOnly, std::vector<int32>& spawned) {
    uint64 rng = m_config.seed ^ (static_cast<uint64>(frame) * 0xD1B54A32D192ED03ULL);
    std::vector<b2Body*> dynamic;
    for (b2Body* b = m_world.GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() == b2_dynamicBody && b->IsActive()) dynamic.push_back(b);
    }
    auto pick = [&]() { return dynamic[static_cast<size_t>(NextRandom(rng) % dynamic.size())]; };
    if (!dynamic.empty()) {
        // Kicks of up to 5 m/s on three bodies.
        for (int i = 0; i < 3; ++i) {
            b2Body* b = pick();
            b->SetLinearVelocity(b->GetLinearVelocity() + b2Vec2(RandomFixed(rng, 5), RandomFixed(rng, 5)));
        }
    }
    const uint64 roll = NextRandom(rng);
    if (roll % 2 == 0) {
        // A new box above a random body (or above the origin).
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position = dynamic.empty() ? b2Vec2(0, 5) : pick()->GetPosition() + b2Vec2(0, Fixed(3) / 2);
        b2Body* body = m_world.CreateBody(&bd);
        b2PolygonShape box;
        box.SetAsBox(Fixed(1) / 4, Fixed(1) / 4);
        body->CreateFixture(&box, 1);
        dynamic.push_back(body);
        spawned.push_back(body->GetId());
    }
    if (roll % 3 == 0) {
        // A joint between two bodies: exercises joint ids and edges. A spawn-only branch joins
        // its own two newest bodies (a spawned ragdoll's joints).
        b2Body* a = nullptr;
        b2Body* b = nullptr;
        if (spawnOnly) {
            if (spawned.size() >= 2) {
                a = m_world.GetBody(spawned[spawned.size() - 1]);
                b = m_world.GetBody(spawned[spawned.size() - 2]);
            }
        } else if (dynamic.size() >= 2) {
            a = pick();
            b = pick();
        }
        if (a != nullptr && b != nullptr && a != b) {
            b2DistanceJointDef jd;
            jd.Initialize(a, b, a->GetWorldCenter(), b->GetWorldCenter());
            m_world.CreateJoint(&jd);
        }
    }
    if (roll % 5 == 0) {
        if (!spawnOnly) {
            if (!dynamic.empty()) m_world.DestroyBody(pick());
        } else if (!spawned.empty()) {
            // One of the branch's own bodies (its slot is reused next). An id the game freed
            // meanwhile is skipped; one it reused holds a body new to the branch too.
            const size_t at = static_cast<size_t>(NextRandom(rng) % spawned.size());
            if (b2Body* victim = m_world.GetBody(spawned[at])) m_world.DestroyBody(victim);
            spawned.erase(spawned.begin() + static_cast<std::ptrdiff_t>(at));
        }
    }
}

SyncTestResult SyncTest::Run(int32 frames) {
    const state_detail::FrameRestoreCounts& counts = core_detail::Engine::Of(m_world).m_frames.m_restores;
    const state_detail::FrameRestoreCounts before = counts;
    SyncTestResult result = RunFrames(frames);
    const state_detail::FrameRestoreCounts after = counts;
    result.frameRestores.sameStructure = after.sameStructure - before.sameStructure;
    result.frameRestores.undoneCreations = after.undoneCreations - before.undoneCreations;
    result.frameRestores.restoredStructure = after.restoredStructure - before.restoredStructure;
    return result;
}

SyncTestResult SyncTest::RunFrames(int32 frames) {
    SyncTestResult result;
    const int32 k = m_config.checkDistance;
    m_hashes.assign(static_cast<size_t>(frames < 0 ? 0 : frames) + 1, 0);
    m_hashes[0] = SaveFrame(0);
    for (int32 f = 0; f < frames; ++f) {
        Advance(f);
        ++result.framesSimulated;
        m_hashes[static_cast<size_t>(f) + 1] = SaveFrame(f + 1);
        if (f + 1 < k || (f + 1 - k) % m_config.stride != 0) continue;
        const int32 from = f + 1 - k;
        if (m_config.mispredict) {
            if (!LoadFrame(from, result)) return result;
            // Every other rollback (counted in strides, so a stride of 8 alternates too).
            const bool spawnOnly = (from / m_config.stride) % 2 != 0;
            std::vector<int32> spawned;
            for (int32 g = from; g <= f; ++g) {
                WrongInputs(g, spawnOnly, spawned);
                Advance(g);
            }
        }
        if (!LoadFrame(from, result)) return result;
        ++result.rollbacks;
        for (int32 g = from; g <= f; ++g) {
            Advance(g);
            ++result.framesResimulated;
            if (!CheckFrame(g + 1, result)) return result;
        }
    }
    return result;
}

}  // namespace lockbox
