#pragma once
/// @file
/// Worker threads for a world's step. A world runs its independent work (the narrow-phase
/// update of every contact, the solve of every island) as parallel loops handed to a
/// b2TaskSystem: either the built-in b2ThreadPool (b2World::SetWorkerCount) or a game's own
/// job system (b2World::SetTaskSystem).
///
/// The result never depends on the workers: every piece of work writes only its own outputs,
/// and the world applies them, with every listener call, in the one-worker order. So any
/// number of workers, any job system and any scheduling give the same bits. One worker is the
/// default, and then no thread is ever created.

#include <memory>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

/// The body of a parallel loop: runs items [begin, end) of it. `context` is the loop's own
/// pointer, handed back unchanged. Called from any thread; it must not be called again for
/// an item it already ran.
using b2TaskRange = void (*)(int32 begin, int32 end, void* context);

/// A job system a world can run its parallel loops on (as Box2D v3's enqueue/finish task
/// callbacks). Implement ParallelFor on top of your scheduler: split, enqueue, wait.
class LOCKBOX_API b2TaskSystem {
public:
    virtual ~b2TaskSystem();

    /// Threads that may run blocks at the same time, the caller's included (>= 1). The world
    /// runs its loops serially, without calling ParallelFor, when this is 1.
    virtual int32 GetWorkerCount() const noexcept = 0;

    /// Runs range over items [0, itemCount) in blocks [k * blockSize, min((k + 1) * blockSize,
    /// itemCount)) and returns when every block has finished. Each block must run exactly
    /// once; blocks may run on any threads (the caller's included), in any order, concurrently.
    /// itemCount >= 1 and blockSize >= 1. Called only by the thread stepping the world (never
    /// from inside a block), so one loop runs at a time per world.
    virtual void ParallelFor(int32 itemCount, int32 blockSize, b2TaskRange range, void* context) = 0;
};

/// The built-in task system: workerCount - 1 threads and the calling thread, all taking blocks
/// from the loop in hand. Between loops the threads watch for the next one for some tens of
/// microseconds, when the process has a core for each of them, and then sleep. The threads are
/// created by the constructor and joined by the destructor.
class LOCKBOX_API b2ThreadPool final : public b2TaskSystem {
public:
    /// A pool of workerCount threads, the caller's included (clamped to [1, 64]; 1 creates none).
    explicit b2ThreadPool(int32 workerCount);
    ~b2ThreadPool() override;
    b2ThreadPool(const b2ThreadPool&) = delete;
    b2ThreadPool& operator=(const b2ThreadPool&) = delete;

    /// The count given to the constructor (clamped).
    int32 GetWorkerCount() const noexcept override;
    /// See b2TaskSystem::ParallelFor. Not reentrant: one loop at a time.
    void ParallelFor(int32 itemCount, int32 blockSize, b2TaskRange range, void* context) override;

private:
    struct Shared;
    std::unique_ptr<Shared> m_shared;
};

}  // namespace lockbox
