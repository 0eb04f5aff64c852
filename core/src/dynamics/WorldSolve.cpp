// b2World::Solve: the island search and the islands' solve (the discrete step).
#include <algorithm>
#include <cstddef>
#include <vector>

#include "dynamics/IslandWalk.h"
#include "dynamics/ProfileTimer.h"
#include "dynamics/WorldState.h"
#include "dynamics/contacts/ContactRules.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {

using World = core_detail::Engine::World;
using core_detail::StageTimer;

namespace {
// Whether the built-in pool should take a step's islands, judged on the islands of the step
// before (islands change little from one step to the next). Waking the pool's sleeping threads
// costs tens of microseconds, recording the islands for them costs instructions, and the serial
// stages after a shared solve read bodies last written on another core: so the pool takes only
// large work, and only when no island holds more than half of it, since a pile that holds most
// of it (rain, a tumbler's drum) leaves the other workers idle for the rest.
bool WorthSharing(int32 islands, int64_t work, int64_t largest) {
    constexpr int64_t kMinSharedWork = 1024;  // bodies + contacts + joints of the step's islands
    return islands >= 2 && work >= kMinSharedWork && 2 * largest <= work;
}

/// Body slots per block of the bodies' finish on the workers, and the fewest slots for which
/// the built-in pool is woken for a walk of them (the island search, the finish); a game's task
/// system gets any walk of more than one block.
constexpr int32 kFinishSlotsPerBlock = 256;
constexpr int32 kMinPoolBodySlots = 1024;

}  // namespace

void World::FinishMotion(b2Body& b) noexcept {
    if (b.IsBullet() || b.IsFastThisStep()) b.m_flags |= b2Body::e_fastFlag;
    // Wrapping after the synchronisation keeps this step's swept AABB exact; the next step
    // starts from the wrapped angle (a and a0 shift by the same whole turns).
    b.WrapAngle();
}

void World::FinishBodySlots(int32 begin, int32 end, void* self) {
    World& world = *static_cast<World*>(self);
    FinishBlock& block = world.m_finishBlocks[static_cast<size_t>(begin / kFinishSlotsPerBlock)];
    block.kept.clear();
    block.saturations = 0;
    const SaturationCapture capture(&block.saturations);
    const b2BroadPhase& broadPhase = world.m_contactManager.m_broadPhase;
    world.m_bodies.ForEachLiveIn(begin, end, [&](b2Body& b) {
        if ((b.m_flags & b2Body::e_islandFlag) == 0 || b.m_type == b2_staticBody) return;
        const b2Transform xf1 = SweepStart(b);
        bool moves = false;
        for (b2Fixture* f = b.m_fixtureList; f; f = f->m_next) {
            if (f->SweepProxies(broadPhase, xf1, b.m_xf)) moves = true;
        }
        const b2Vec2 displacement = b.m_xf.p - xf1.p;
        FinishMotion(b);
        const bool outside = world.IsOutside(&b);
        if (moves || outside) block.kept.push_back({&b, displacement, moves, outside});
    });
}

void World::FinishBodiesOnWorkers(b2TaskSystem& tasks) {
    const int32 slots = m_bodies.GetCapacity();
    const int32 blocks = (slots + kFinishSlotsPerBlock - 1) / kFinishSlotsPerBlock;
    if (m_finishBlocks.size() < static_cast<size_t>(blocks)) m_finishBlocks.resize(static_cast<size_t>(blocks));
    tasks.ParallelFor(slots, kFinishSlotsPerBlock, &FinishBodySlots, this);

    // What touches the world goes on here, in body-list order: the broad phase's moves (the
    // tree and the move buffer) and the bodies outside the bounds.
    m_finished.clear();
    uint64 saturations = 0;
    for (int32 k = 0; k < blocks; ++k) {
        const FinishBlock& block = m_finishBlocks[static_cast<size_t>(k)];
        m_finished.insert(m_finished.end(), block.kept.begin(), block.kept.end());
        saturations += block.saturations;
    }
    AddSaturations(saturations);
    std::sort(m_finished.begin(), m_finished.end(),
              [](const FinishedBody& a, const FinishedBody& b) { return a.body->m_listKey < b.body->m_listKey; });
    b2BroadPhase* broadPhase = &m_contactManager.m_broadPhase;
    for (const FinishedBody& f : m_finished) {
        if (f.moves) {
            for (b2Fixture* fixture = f.body->m_fixtureList; fixture; fixture = fixture->m_next)
                fixture->MoveProxies(broadPhase, f.displacement);
        }
        if (f.outside) m_outOfBounds.push_back(f.body);
    }
}

void World::Solve(const b2TimeStep& step) {
    // Size the island for the worst case.
    m_island.Reset(m_bodyCount, m_contactManager.m_contactCount, m_jointCount, m_contactManager.m_contactListener);
    m_island.m_observer = m_stepObserver;
    // With workers the islands are found first and solved together; the island fenceposts of a
    // step observer (replay bisection) need them one at a time, so an observer keeps one worker.
    // The built-in pool gets them only when the last step's islands were worth sharing; which
    // path runs changes no result.
    b2TaskSystem* tasks = Tasks();
    const bool hasWorkers = tasks != nullptr && tasks->GetWorkerCount() > 1 && m_stepObserver == nullptr;
    const bool parallel = hasWorkers && (!OnOwnPool() || m_shareIslands);
    // The islands' sizes, for the pool's choice in the next step (not counted with one worker).
    const bool measure = hasWorkers && OnOwnPool();
    IslandTally tally;
    // Many body slots are walked by the workers: in the island search when the islands are
    // solved together, and in the bodies' finish.
    const int32 bodySlots = m_bodies.GetCapacity();
    const bool manyBodies = hasWorkers && bodySlots >= (OnOwnPool() ? kMinPoolBodySlots : kFinishSlotsPerBlock + 1);
    m_jointGraph.Refresh(m_bodyList, bodySlots);
    if (parallel && manyBodies) {
        FindIslandsOnWorkers(*tasks, tally);
    } else {
        SearchIslands(step, tasks, hasWorkers, parallel, measure, tally);
    }
    if (parallel) SolveRecordedIslands(step, *tasks);
    if (measure) m_shareIslands = WorthSharing(tally.islands, tally.work, tally.largest);
    if (m_stepObserver != nullptr) m_stepObserver->OnStage(b2StepStage::e_solve, *m_owner);

    const StageTimer timer(step.timers);
    if (manyBodies) {
        FinishBodiesOnWorkers(*tasks);
    } else {
        // Synchronise fixtures of bodies that moved, keep angles bounded, flag fast bodies and
        // collect bodies that left the world.
        for (b2Body* b = m_bodyList; b; b = b->GetNext()) {
            if ((b->m_flags & b2Body::e_islandFlag) == 0) continue;
            if (b->GetType() == b2_staticBody) continue;
            SynchronizeFixtures(*b);
            FinishMotion(*b);
            if (IsOutside(b)) m_outOfBounds.push_back(b);
        }
    }
    m_contactManager.FindNewContacts(tasks, MinParallelBroadPhase());
    m_profile.broadphaseNs += timer.Nanos();
    if (m_stepObserver != nullptr) m_stepObserver->OnStage(b2StepStage::e_broadPhase, *m_owner);
}

void World::SearchIslands(const b2TimeStep& step, b2TaskSystem* tasks, bool hasWorkers, bool parallel, bool measure,
                          IslandTally& tally) {
    // Clear the graph flags.
    m_bodies.ForEachLive([](b2Body& b) { b.m_flags &= ~(b2Body::e_islandFlag | b2Body::e_fastFlag); });
    m_contactManager.ForEachInSlots(0, m_contactManager.SlotCount(),
                                    [](b2Contact& c) { c.m_flags &= ~b2Contact::e_islandFlag; });

    m_stack.reserve(static_cast<size_t>(m_bodyCount));

    for (b2Body* seed = m_bodyList; seed; seed = seed->m_next) {
        if (seed->m_flags & b2Body::e_islandFlag) continue;
        if (!seed->IsAwake() || !seed->IsActive()) continue;
        // The seed can be dynamic or kinematic.
        if (seed->GetType() == b2_staticBody) continue;

        m_island.Clear();
        m_islandStatics.clear();
        // Static bodies are marked by their island flag too, and woken; the marks are cleared
        // after the island, since other islands may take them.
        struct Sink {
            World& w;
            void Body(b2Body* b) { w.m_island.Add(b); }
            void Static(b2Body* b) {
                b->SetAwake(true);
                // The few an island holds are noted, so that what is done to them after its
                // solve visits no other body.
                w.m_islandStatics.push_back(b);
            }
            void Contact(b2Contact* c) { w.m_island.Add(c); }
            void Joint(b2Joint* j) { w.m_island.Add(j); }
            bool Meet(b2Body& b) {
                if (b.m_flags & b2Body::e_islandFlag) return false;
                b.m_flags |= b2Body::e_islandFlag;
                return true;
            }
        } sink{*this};
        WalkIsland(seed, m_jointGraph, m_stack, sink);

        // No other island reaches these bodies: the scan marks have served, and the solve (and
        // any observer's view of it) sees the flags as they were.
        ClearScanMarks({m_island.m_bodies.data(), static_cast<size_t>(m_island.m_bodyCount)});

        if (measure) tally.Add(m_island.m_bodyCount + m_island.m_contactCount + m_island.m_jointCount);
        if (parallel) {
            RecordIsland();
        } else {
            // A coloured island solved here is shared colour by colour between the workers.
            m_island.m_tasks = hasWorkers ? tasks : nullptr;
            const bool slept = m_island.Solve(&m_profile, step, m_gravity, m_allowSleep);
            m_island.m_tasks = nullptr;
            // 2.2.1 sets every body of a sleeping island asleep; the solve leaves static
            // bodies, which islands share, alone.
            if (slept) {
                for (b2Body* b : m_islandStatics) b->SetAwake(false);
            }
            ++m_profile.islandsSolved;
        }

        // Static bodies may take part in other islands.
        for (b2Body* b : m_islandStatics) b->m_flags &= ~b2Body::e_islandFlag;
    }
}

}  // namespace lockbox
