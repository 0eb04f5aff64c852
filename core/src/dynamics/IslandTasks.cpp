// A step's islands solved at the same time on the world's task system.
//
// Islands share nothing they write: a dynamic or kinematic body, a contact and a joint belong to
// one island. Static bodies are shared, so no island solve writes one: each keeps one solver
// slot for the whole step (below every island's own bodies, b2Island::m_slotBase), its state
// is only read, and what 2.2.1 writes into it (sleep with its island) is done afterwards, in
// island order. Everything an island solve reports (PostSolve impulses, saturations, work
// counters) is kept per island and applied in island order too, so the result is that of the
// one-worker loop in World::Solve, whatever the workers and their scheduling.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "dynamics/WorldState.h"
#include "dynamics/tasks/ScratchSet.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {

using World = core_detail::Engine::World;

struct World::ParallelIslands {
    /// Where one island's lists start in the flat arrays; the next island's starts end them
    /// (a last entry closes the final island).
    struct Start {
        int32 body = 0;
        int32 contact = 0;
        int32 joint = 0;
        int32 statics = 0;
    };
    /// A solver's buffers, taken by one block of islands at a time.
    struct Scratch {
        b2Island island;
        b2Profile profile;  ///< the island counters of the blocks it solved
    };

    std::vector<Start> starts;
    std::vector<b2Body*> bodies;
    std::vector<b2Contact*> contacts;
    std::vector<b2Joint*> joints;
    std::vector<b2Body*> statics;            ///< each island's static bodies, in island order
    std::vector<uint8> slept;                ///< per island
    std::vector<uint64_t> saturations;       ///< per island, counted while it was solved
    std::vector<b2ContactImpulse> impulses;  ///< per contact, for PostSolve
    std::vector<int32> order;                ///< islands in the order the blocks take them
    std::vector<int32> staged;               ///< islands solved one by one, each by every worker
    std::vector<int32> sizes;                ///< per island: bodies + contacts + joints
    b2ScratchSet<Scratch> scratch;

    // The step being solved.
    const b2TimeStep* step = nullptr;
    b2Vec2 gravity;
    bool allowSleep = true;
    bool reportImpulses = false;

    int32 IslandCount() const noexcept { return static_cast<int32>(starts.size()) - 1; }

    void SolveIsland(b2Island& island, b2Profile& profile, int32 i) {
        const Start& from = starts[static_cast<size_t>(i)];
        const Start& to = starts[static_cast<size_t>(i) + 1];
        island.Clear();
        for (int32 k = from.body; k < to.body; ++k) island.Add(bodies[static_cast<size_t>(k)]);
        for (int32 k = from.contact; k < to.contact; ++k) island.Add(contacts[static_cast<size_t>(k)]);
        for (int32 k = from.joint; k < to.joint; ++k) island.Add(joints[static_cast<size_t>(k)]);
        island.m_impulseSink = reportImpulses ? impulses.data() + from.contact : nullptr;
        uint64_t count = 0;
        {
            const SaturationCapture capture(&count);
            slept[static_cast<size_t>(i)] = island.Solve(&profile, *step, gravity, allowSleep) ? 1 : 0;
        }
        saturations[static_cast<size_t>(i)] = count;
        // A coloured island solved its contacts, and recorded their impulses, in colour order:
        // its PostSolve calls go in that order too, as with one worker.
        if (island.ColoursContacts()) {
            std::copy(island.m_contacts.begin(), island.m_contacts.begin() + (to.contact - from.contact),
                      contacts.begin() + from.contact);
        }
    }

    // Fills `staged` with the coloured islands that hold more than a worker's share of the
    // work (bodies, contacts and joints), in island order: blocks of whole islands would leave
    // the other workers idle while one of these is solved, so each is shared colour by colour
    // instead (b2Island::m_tasks). Fills `order` with the other islands that hold more than an
    // eighth of a worker's share, largest first, equal sizes in island order (a key without
    // ties); then every other island, in island order. The big ones decide how even the
    // workers' loads end up; the small ones fill the gaps in any order, and sorting them too
    // cost tumbler's two thousand one-body islands more than they took to solve.
    void OrderLargestFirst(int32 workers) {
        const int32 count = IslandCount();
        sizes.resize(static_cast<size_t>(count));
        int64_t work = 0;
        for (int32 i = 0; i < count; ++i) {
            const Start& from = starts[static_cast<size_t>(i)];
            const Start& to = starts[static_cast<size_t>(i) + 1];
            sizes[static_cast<size_t>(i)] =
                (to.body - from.body) + (to.contact - from.contact) + (to.joint - from.joint);
            work += sizes[static_cast<size_t>(i)];
        }
        staged.clear();
        for (int32 i = 0; i < count; ++i) {
            const Start& from = starts[static_cast<size_t>(i)];
            const Start& to = starts[static_cast<size_t>(i) + 1];
            const bool coloured = b2Coloured(to.contact - from.contact) || b2Coloured(to.joint - from.joint);
            if (coloured && int64_t{sizes[static_cast<size_t>(i)]} * workers > work) {
                staged.push_back(i);
                sizes[static_cast<size_t>(i)] = -1;  // taken
            }
        }
        const int64_t big = work / (8 * static_cast<int64_t>(workers));
        order.clear();
        for (int32 i = 0; i < count; ++i) {
            if (sizes[static_cast<size_t>(i)] > big) order.push_back(i);
        }
        std::sort(order.begin(), order.end(), [this](int32 a, int32 b) {
            const int32 sa = sizes[static_cast<size_t>(a)], sb = sizes[static_cast<size_t>(b)];
            return sa != sb ? sa > sb : a < b;
        });
        for (int32 i = 0; i < count; ++i) {
            const int32 size = sizes[static_cast<size_t>(i)];
            if (size >= 0 && size <= big) order.push_back(i);
        }
    }

    // Solves the islands order[begin..end).
    static void SolveRange(int32 begin, int32 end, void* context) {
        auto* self = static_cast<ParallelIslands*>(context);
        const b2ScratchSet<Scratch>::Lease s = self->scratch.Acquire();
        for (int32 i = begin; i < end; ++i)
            self->SolveIsland(s->island, s->profile, self->order[static_cast<size_t>(i)]);
    }
};

void World::ParallelIslandsDeleter::operator()(ParallelIslands* p) const noexcept { delete p; }

namespace {
// The counters b2Island::Solve adds to a profile (its PostSolve calls are counted when the
// world makes them).
void AddIslandCounters(b2Profile& to, b2Profile& from) {
    to.solveInitNs += from.solveInitNs;
    to.solveVelocityNs += from.solveVelocityNs;
    to.solvePositionNs += from.solvePositionNs;
    to.bodiesIntegrated += from.bodiesIntegrated;
    to.contactConstraints += from.contactConstraints;
    to.jointConstraints += from.jointConstraints;
    to.velocityIterations += from.velocityIterations;
    to.jointVelocityIterations += from.jointVelocityIterations;
    to.positionIterations += from.positionIterations;
    to.sleepChecks += from.sleepChecks;
    from = b2Profile();
}
}  // namespace

void World::RecordIsland() {
    const auto n = [](int32 count) { return static_cast<size_t>(count); };
    RecordIsland({m_island.m_bodies.data(), n(m_island.m_bodyCount)},
                 {m_island.m_contacts.data(), n(m_island.m_contactCount)},
                 {m_island.m_joints.data(), n(m_island.m_jointCount)}, m_islandStatics);
}

void World::RecordIsland(std::span<b2Body* const> bodies, std::span<b2Contact* const> contacts,
                         std::span<b2Joint* const> joints, std::span<b2Body* const> statics) {
    if (!m_parallelIslands) m_parallelIslands.reset(new ParallelIslands);
    ParallelIslands& p = *m_parallelIslands;
    if (p.starts.empty()) p.starts.push_back({});
    p.bodies.insert(p.bodies.end(), bodies.begin(), bodies.end());
    p.contacts.insert(p.contacts.end(), contacts.begin(), contacts.end());
    p.joints.insert(p.joints.end(), joints.begin(), joints.end());
    p.statics.insert(p.statics.end(), statics.begin(), statics.end());
    p.starts.push_back({static_cast<int32>(p.bodies.size()), static_cast<int32>(p.contacts.size()),
                        static_cast<int32>(p.joints.size()), static_cast<int32>(p.statics.size())});
}

void World::SolveRecordedIslands(const b2TimeStep& step, b2TaskSystem& tasks) {
    if (!m_parallelIslands) return;  // no island this step
    ParallelIslands& p = *m_parallelIslands;
    const int32 islandCount = p.IslandCount();
    if (islandCount <= 0) {
        p.starts.clear();
        return;
    }

    // Every static body of the step's islands gets its step-long slot, numbered as the islands
    // first reach it (a body shared by islands is listed once per island); the islands' own
    // bodies go above them. Which slot a static body takes changes no result: each island
    // copies its static bodies into its own buffers, and the colours leave them out.
    for (b2Body* b : p.statics) b->m_islandIndex = -1;
    int32 statics = 0;
    for (b2Body* b : p.statics) {
        if (b->m_islandIndex < 0) b->m_islandIndex = statics++;
    }
    int32 maxBodies = 0, maxContacts = 0, maxJoints = 0;
    for (int32 i = 0; i < islandCount; ++i) {
        const ParallelIslands::Start& from = p.starts[static_cast<size_t>(i)];
        const ParallelIslands::Start& to = p.starts[static_cast<size_t>(i) + 1];
        maxBodies = b2Max(maxBodies, to.body - from.body);
        maxContacts = b2Max(maxContacts, to.contact - from.contact);
        maxJoints = b2Max(maxJoints, to.joint - from.joint);
    }
    const int32 workers = tasks.GetWorkerCount();
    p.scratch.Reserve(workers);
    b2ContactListener* listener = m_contactManager.m_contactListener;
    p.scratch.ForEach(
        [&](ParallelIslands::Scratch& s) { s.island.Reset(maxBodies, maxContacts, maxJoints, listener, statics); });

    p.step = &step;
    p.gravity = m_gravity;
    p.allowSleep = m_allowSleep;
    p.reportImpulses = listener != nullptr;
    p.slept.assign(static_cast<size_t>(islandCount), 0);
    p.saturations.assign(static_cast<size_t>(islandCount), 0);
    if (p.reportImpulses) p.impulses.assign(p.contacts.size(), b2ContactImpulse());

    p.OrderLargestFirst(workers);
    for (const int32 i : p.staged) {
        ParallelIslands::Scratch& s = p.scratch.Front();
        s.island.m_tasks = &tasks;
        p.SolveIsland(s.island, s.profile, i);
        s.island.m_tasks = nullptr;
    }
    const auto blocks = static_cast<int32>(p.order.size());
    if (blocks == 1) {
        ParallelIslands::SolveRange(0, 1, &p);
    } else if (blocks > 1) {
        // A few blocks per worker: islands differ in size, and blocks taken as workers free up
        // even the load out. The largest islands go first (the longest-first rule of
        // scheduling): a big island taken last would leave the other workers idle, and the first
        // block, which the calling thread usually takes, keeps the step's largest island on the
        // thread that runs the serial stages, whose caches then already hold it. The order of
        // the work changes no result: the finish below goes in island order.
        const int32 blockSize = b2Max(1, blocks / (4 * workers));
        tasks.ParallelFor(blocks, blockSize, &ParallelIslands::SolveRange, &p);
    }

    // Finish in island order, as the one-worker loop does after each island.
    for (int32 i = 0; i < islandCount; ++i) {
        const ParallelIslands::Start& from = p.starts[static_cast<size_t>(i)];
        const ParallelIslands::Start& to = p.starts[static_cast<size_t>(i) + 1];
        AddSaturations(p.saturations[static_cast<size_t>(i)]);
        // The search woke the island's static bodies (in the one-worker loop, after the
        // previous islands had been solved): wake them again, then let them sleep with it.
        const bool slept = p.slept[static_cast<size_t>(i)] != 0;
        for (int32 k = from.statics; k < to.statics; ++k) {
            b2Body* b = p.statics[static_cast<size_t>(k)];
            b->SetAwake(true);
            if (slept) b->SetAwake(false);
        }
        if (p.reportImpulses) {
            for (int32 k = from.contact; k < to.contact; ++k) {
                listener->PostSolve(p.contacts[static_cast<size_t>(k)], &p.impulses[static_cast<size_t>(k)]);
                ++m_profile.listenerCallbacks;
            }
        }
        ++m_profile.islandsSolved;
    }
    p.scratch.ForEach([&](ParallelIslands::Scratch& s) { AddIslandCounters(m_profile, s.profile); });

    p.starts.clear();
    p.bodies.clear();
    p.contacts.clear();
    p.joints.clear();
    p.statics.clear();
}

}  // namespace lockbox
