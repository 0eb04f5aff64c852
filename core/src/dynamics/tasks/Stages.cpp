// b2Stages: blocks claimed from per-stage counters; the last block of a stage opens the next.
#include "dynamics/tasks/Stages.h"

#include <algorithm>
#include <thread>

#include "dynamics/tasks/SpinPause.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {

namespace {
// A short pause in a wait loop; after a while the thread gives up its core, so that a worker
// the system descheduled can run (the waits here last microseconds when every worker runs).
void Relax(int32& spins) {
    if (spins < 256) {
        ++spins;
        SpinPause();
        return;
    }
    std::this_thread::yield();
}
}  // namespace

int32 b2Stages::Add(int32 blockCount) {
    m_blockCounts.push_back(blockCount);
    return static_cast<int32>(m_blockCounts.size()) - 1;
}

void b2Stages::Run(b2TaskSystem& tasks, Block block, Next next, void* context) {
    const int32 count = Count();
    if (count == 0) return;
    m_workers = tasks.GetWorkerCount();
    const auto stages = static_cast<size_t>(count);
    const size_t claims = stages * static_cast<size_t>(m_workers);
    if (m_doneCapacity < stages) {
        m_done = std::make_unique<Counter[]>(stages);
        m_doneCapacity = stages;
    }
    if (m_claimCapacity < claims) {
        m_claims = std::make_unique<Counter[]>(claims);
        m_claimCapacity = claims;
    }
    for (size_t s = 0; s < stages; ++s) m_done[s].value.store(0, std::memory_order_relaxed);
    for (size_t c = 0; c < claims; ++c) m_claims[c].value.store(0, std::memory_order_relaxed);
    m_block = block;
    m_next = next;
    m_context = context;
    m_saturations.store(0, std::memory_order_relaxed);
    m_stage.store(0, std::memory_order_relaxed);
    // The task system's loop start orders these writes before every worker's first read.
    tasks.ParallelFor(m_workers, 1, &b2Stages::Participate, this);
    AddSaturations(m_saturations.load(std::memory_order_relaxed));
}

void b2Stages::Participate(int32 begin, int32 end, void* self) {
    for (int32 worker = begin; worker < end; ++worker) static_cast<b2Stages*>(self)->Work(worker);
}

int32 b2Stages::Claim(int32 stage, int32 worker) noexcept {
    const int32 blocks = m_blockCounts[static_cast<size_t>(stage)];
    for (int32 k = 0; k < m_workers; ++k) {
        const int32 share = (worker + k) % m_workers;
        const int32 first = ShareStart(blocks, share);
        const int32 size = ShareStart(blocks, share + 1) - first;
        if (size == 0) continue;
        Counter& claimed =
            m_claims[static_cast<size_t>(stage) * static_cast<size_t>(m_workers) + static_cast<size_t>(share)];
        // A relaxed load first: a share that is done is passed over without writing its line.
        if (claimed.value.load(std::memory_order_relaxed) >= size) continue;
        const int32 index = claimed.value.fetch_add(1, std::memory_order_relaxed);
        if (index < size) return first + index;
    }
    return -1;
}

void b2Stages::Work(int32 worker) {
    const int32 count = Count();
    uint64_t saturations = 0;
    {
        const SaturationCapture capture(&saturations);
        int32 spins = 0;
        for (;;) {
            // Acquire: the blocks of the stages before are visible (see the release below).
            const int32 stage = m_stage.load(std::memory_order_acquire);
            if (stage >= count) break;
            const int32 block = Claim(stage, worker);
            if (block < 0) {
                // Nothing left to claim: wait until the workers on this stage's blocks finish.
                while (m_stage.load(std::memory_order_relaxed) == stage) Relax(spins);
                spins = 0;
                continue;
            }
            m_block(stage, block, m_context);
            // acq_rel: the worker that finishes a stage has seen every block's writes, and its
            // release store of the next stage hands them to all.
            const int32 blocks = m_blockCounts[static_cast<size_t>(stage)];
            if (m_done[static_cast<size_t>(stage)].value.fetch_add(1, std::memory_order_acq_rel) + 1 == blocks) {
                // A stage's counters serve once: the run only moves forward.
                const int32 following =
                    m_next == nullptr ? stage + 1 : std::clamp(m_next(stage, m_context), stage + 1, count);
                m_stage.store(following, std::memory_order_release);
            }
        }
    }
    m_saturations.fetch_add(saturations, std::memory_order_relaxed);
}

}  // namespace lockbox
