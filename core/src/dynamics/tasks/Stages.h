#pragma once
// Stages: a sequence of steps run by every worker of a task system in one parallel loop. A
// stage is a set of blocks that may run at the same time, in any order; the next stage starts
// when every block of this one has finished. The colour order of a large island's solver is
// such a sequence (a colour's contacts share no dynamic body), and one loop for all of it
// spares a wake-up of the workers per colour.
//
// Each worker first takes the blocks of its own share of a stage (the same share in every
// stage of the same range, so that a colour's constraints stay in one core's cache from one
// iteration to the next), then helps with the other shares. No worker waits for a particular
// other one: whichever finishes a stage's last block opens the next, and a worker that finds
// nothing left to claim waits only for blocks that others are running. So a task system that
// runs the loop's items one after the other (or fewer at once than it has workers) still
// finishes: the first item then does all the work and the others find it done.

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "lockbox/common/Settings.h"

namespace lockbox {

class b2TaskSystem;

class b2Stages {
public:
    /// Runs block `block` of stage `stage`.
    using Block = void (*)(int32 stage, int32 block, void* context);
    /// Called once when stage `stage` has finished, by the worker that finished its last block,
    /// before any other stage starts; returns the stage to run next, which must come after
    /// `stage` (Count() ends the run). Without one, the stages run in order.
    using Next = int32 (*)(int32 stage, void* context);

    /// Appends a stage of `blockCount` blocks (>= 1) and returns its index.
    int32 Add(int32 blockCount);
    /// Removes every stage.
    void Clear() noexcept { m_blockCounts.clear(); }
    int32 Count() const noexcept { return static_cast<int32>(m_blockCounts.size()); }

    /// Runs the stages on `tasks` (GetWorkerCount() > 1), from the first, in order or as `next`
    /// says, and returns when the run has ended. Every worker's saturations are counted on the calling
    /// thread. Called by the thread stepping the world, never from inside a loop.
    void Run(b2TaskSystem& tasks, Block block, Next next, void* context);

private:
    // One cache line each: workers claim from their own share without touching the others'.
    struct alignas(64) Counter {
        std::atomic<int32> value{0};
    };
    static void Participate(int32 begin, int32 end, void* self);
    void Work(int32 worker);
    // Claims a block of `stage` for `worker`: its own share first, then the others' in turn.
    // Returns -1 when every block of the stage is claimed.
    int32 Claim(int32 stage, int32 worker) noexcept;
    // Share w of a stage of n blocks: blocks [n w / W, n (w + 1) / W).
    int32 ShareStart(int32 blocks, int32 share) const noexcept {
        return static_cast<int32>(static_cast<int64_t>(blocks) * share / m_workers);
    }

    std::vector<int32> m_blockCounts;
    std::unique_ptr<Counter[]> m_done;    ///< per stage: blocks finished
    std::unique_ptr<Counter[]> m_claims;  ///< per stage and share: blocks of the share claimed
    size_t m_doneCapacity = 0, m_claimCapacity = 0;
    int32 m_workers = 1;
    std::atomic<int32> m_stage{0};  ///< the open stage; Count() once the run has ended
    std::atomic<uint64_t> m_saturations{0};
    Block m_block = nullptr;
    Next m_next = nullptr;
    void* m_context = nullptr;
};

}  // namespace lockbox
