// b2Island's shared solve: a coloured island's velocity and position loops as stages run by
// every worker. Each stage is one colour (or work that any split does alike), so the result is
// the colour order's, bit for bit, with any number of workers.
#include "dynamics/IslandShared.h"

#include <algorithm>

#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Tasks.h"

namespace lockbox {

namespace {
using Shared = b2Island::Shared;
using Kind = Shared::Kind;

// Items per block: many blocks per worker, since a worker that finishes its share first waits
// at the stage's end for the block still running elsewhere; but not so few items that claiming
// a block costs more than solving it.
int32 BlockSize(int32 items, int32 workers) {
    constexpr int32 kMinItems = 16;
    constexpr int32 kBlocksPerWorker = 16;
    const int32 share = (items + kBlocksPerWorker * workers - 1) / (kBlocksPerWorker * workers);
    return std::max(kMinItems, share);
}

// How a stage's items are taken: split into blocks, split into blocks of one colour (whose items
// write no body in common), or in one block, in order.
enum class StageSplit { e_blocks, e_colour, e_serial };

// A stage over items [begin, end).
void AddStage(Shared& s, Kind kind, int32 begin, int32 end, int32 workers, StageSplit split = StageSplit::e_blocks) {
    if (end <= begin) return;
    Shared::Stage stage;
    stage.kind = kind;
    stage.oneColour = split == StageSplit::e_colour;
    stage.begin = begin;
    stage.end = end;
    stage.blockSize = split == StageSplit::e_serial ? end - begin : BlockSize(end - begin, workers);
    // A colour's blocks are cut where the contact lanes' quads begin (Stage::Grid), so that no
    // quad is split between two blocks (and solved by the scalar row).
    if (stage.oneColour) stage.blockSize = b2LaneQuad::CeilBoundary(stage.blockSize);
    s.plan.push_back(stage);
    s.stages.Add((end - stage.Grid() + stage.blockSize - 1) / stage.blockSize);
}

// One stage per colour (its constraints write no body in common), split between the workers.
// A colour too small to be worth a wait at its end runs on one worker, together with the small
// colours after it and the overflow when it follows: one block in colour order, which is the
// order of separate stages (a drum that touches hundreds of boxes leaves one contact in each of
// its last colours).
template <class Item>
void AddColourStages(Shared& s, Kind kind, const b2Colours<Item>& colours, int32 workers) {
    constexpr int32 kMinSharedPerWorker = 32;
    int32 serialBegin = -1;  // the first small colour not yet in a stage
    for (int32 c = 0; c <= b2_colourCount; ++c) {
        const int32 begin = colours.Start(c), end = colours.Start(c + 1);
        if (c == b2_colourCount || end - begin < kMinSharedPerWorker * workers) {
            if (serialBegin < 0) serialBegin = begin;
            continue;
        }
        if (serialBegin >= 0) AddStage(s, kind, serialBegin, begin, workers, StageSplit::e_serial);
        serialBegin = -1;
        AddStage(s, kind, begin, end, workers, StageSplit::e_colour);
    }
    if (serialBegin >= 0)
        AddStage(s, kind, serialBegin, colours.Start(b2_colourCount + 1), workers, StageSplit::e_serial);
}

// A kind of constraint stage over `count` constraints: by colour when they were coloured, else
// all of them in island order on one worker.
template <class Item>
void AddConstraintStages(Shared& s, Kind kind, const b2Colours<Item>& colours, int32 count, int32 workers) {
    if (b2Coloured(count)) {
        AddColourStages(s, kind, colours, workers);
    } else {
        AddStage(s, kind, 0, count, workers, StageSplit::e_serial);
    }
}

Shared& Prepare(std::unique_ptr<Shared>& shared, b2Island& island, b2ContactSolver& contacts,
                const b2SolverData& data) {
    if (!shared) shared = std::make_unique<Shared>();
    Shared& s = *shared;
    s.stages.Clear();
    s.plan.clear();
    s.island = &island;
    s.contacts = &contacts;
    s.data = &data;
    return s;
}
}  // namespace

void Shared::RunBlock(int32 stage, int32 block, void* context) {
    Shared& s = *static_cast<Shared*>(context);
    const Shared::Stage& st = s.plan[static_cast<size_t>(stage)];
    const int32 begin = std::max(st.begin, st.Grid() + block * st.blockSize);
    const int32 end = std::min(st.end, st.Grid() + (block + 1) * st.blockSize);
    b2Island& island = *s.island;
    const b2SolverData& data = *s.data;
    switch (st.kind) {
        case Kind::e_integrateVelocities: island.IntegrateVelocities(begin, end, data.step.dt, s.gravity); break;
        case Kind::e_rotations:
            for (int32 i = begin; i < end; ++i) {
                const int32 slot = island.m_bodies[static_cast<size_t>(i)]->m_islandIndex;
                data.rotations[slot].For(data.positions[slot].a);
            }
            break;
        case Kind::e_setUp: s.contacts->SetUp(begin, end); break;
        case Kind::e_warmStart: s.contacts->WarmStart(begin, end); break;
        case Kind::e_jointInit:
            island.m_jointSolver.InitVelocityConstraints(island.m_joints.data(), begin, end, data);
            break;
        case Kind::e_jointVelocity:
            if (st.oneColour) {
                island.m_jointSolver.SolveIndependentVelocityConstraints(data, begin, end);
            } else {
                island.m_jointSolver.SolveVelocityConstraints(data, begin, end);
            }
            break;
        case Kind::e_velocity:
            if (st.oneColour) {
                s.contacts->SolveIndependentVelocityConstraints(begin, end);
            } else {
                s.contacts->SolveVelocityConstraints(begin, end);
            }
            break;
        case Kind::e_storeImpulses: s.contacts->StoreImpulses(begin, end); break;
        case Kind::e_jointStoreImpulses: island.m_jointSolver.StoreImpulses(begin, end); break;
        case Kind::e_integratePositions: island.IntegratePositions(begin, end, data.step.dt); break;
        case Kind::e_position: {
            const int32 raw = s.contacts->SolvePositionConstraints(begin, end).Raw();
            int32 seen = s.minSeparation.load(std::memory_order_relaxed);
            while (raw < seen && !s.minSeparation.compare_exchange_weak(seen, raw, std::memory_order_relaxed)) {
            }
            break;
        }
        case Kind::e_jointPosition:
            if (!island.m_jointSolver.SolvePositionConstraints(data, begin, end))
                s.jointsOkay.store(false, std::memory_order_relaxed);
            break;
        case Kind::e_storeBodies: island.StoreBodies(begin, end); break;
    }
}

// After each position iteration (its last stage): an accepted iteration skips the remaining
// iterations, as the one-thread loop does, and goes on to the copy back.
int32 Shared::NextPositionStage(int32 stage, void* context) {
    Shared& s = *static_cast<Shared*>(context);
    if (!s.plan[static_cast<size_t>(stage)].endsIteration) return stage + 1;
    ++s.positionIterations;
    const bool okay =
        b2ContactSolver::PositionAccepted(Fixed::FromRaw(s.minSeparation.load(std::memory_order_relaxed))) &&
        s.jointsOkay.load(std::memory_order_relaxed);
    if (okay) {
        s.positionSolved = true;
        return s.storeStage;
    }
    s.minSeparation.store(0, std::memory_order_relaxed);
    s.jointsOkay.store(true, std::memory_order_relaxed);
    return stage + 1;
}

void b2Island::SolveVelocitiesShared(b2ContactSolver& contacts, const b2SolverData& data, const b2Vec2& gravity) {
    Shared& s = Prepare(m_shared, *this, contacts, data);
    s.gravity = gravity;
    const int32 workers = m_tasks->GetWorkerCount();
    AddStage(s, Kind::e_integrateVelocities, 0, m_bodyCount, workers);
    // The rotations before the set-up, so that the stages after only read a shared body's cache.
    AddStage(s, Kind::e_rotations, 0, m_bodyCount, workers);
    AddStage(s, Kind::e_setUp, 0, m_contactCount, workers);
    if (data.step.warmStarting) AddConstraintStages(s, Kind::e_warmStart, m_contactColours, m_contactCount, workers);
    if (m_jointCount > 0) m_jointSolver.Begin(m_jointCount);
    AddConstraintStages(s, Kind::e_jointInit, m_jointColours, m_jointCount, workers);
    for (int32 it = 0; it < data.step.velocityIterations; ++it) {
        AddConstraintStages(s, Kind::e_jointVelocity, m_jointColours, m_jointCount, workers);
        AddConstraintStages(s, Kind::e_velocity, m_contactColours, m_contactCount, workers);
    }
    // The impulses kept for the next step's warm start: each item writes only its own.
    AddStage(s, Kind::e_storeImpulses, 0, m_contactCount, workers);
    AddStage(s, Kind::e_jointStoreImpulses, 0, m_jointCount, workers);
    s.stages.Run(*m_tasks, &Shared::RunBlock, nullptr, &s);
}

bool b2Island::SolvePositionsShared(b2ContactSolver& contacts, const b2SolverData& data, int32* iterationsRun) {
    Shared& s = Prepare(m_shared, *this, contacts, data);
    const int32 workers = m_tasks->GetWorkerCount();
    AddStage(s, Kind::e_integratePositions, 0, m_bodyCount, workers);
    // Integration turned the kinematic bodies: their rotations too are brought up to date first.
    AddStage(s, Kind::e_rotations, 0, m_bodyCount, workers);
    for (int32 it = 0; it < data.step.positionIterations; ++it) {
        AddConstraintStages(s, Kind::e_position, m_contactColours, m_contactCount, workers);
        AddConstraintStages(s, Kind::e_jointPosition, m_jointColours, m_jointCount, workers);
        // A coloured island has constraints: the iteration added stages, and this is its last.
        s.plan.back().endsIteration = true;
    }
    s.storeStage = static_cast<int32>(s.plan.size());
    AddStage(s, Kind::e_storeBodies, 0, m_bodyCount, workers);
    s.minSeparation.store(0, std::memory_order_relaxed);
    s.jointsOkay.store(true, std::memory_order_relaxed);
    s.positionIterations = 0;
    s.positionSolved = false;
    s.stages.Run(*m_tasks, &Shared::RunBlock, &Shared::NextPositionStage, &s);
    *iterationsRun = s.positionIterations;
    return s.positionSolved;
}

}  // namespace lockbox
