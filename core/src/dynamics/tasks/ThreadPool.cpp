// b2ThreadPool: a fixed set of threads that, between loops, watch for the next one for a moment
// and then sleep on a condition variable, and take blocks of the loop in hand from one atomic
// counter, the calling thread with them.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "dynamics/tasks/SpinPause.h"
#include "lockbox/dynamics/Tasks.h"

#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#include <sched.h>
#endif

namespace lockbox {

b2TaskSystem::~b2TaskSystem() = default;

namespace {
constexpr int32 kMaxWorkers = 64;

// How long a worker keeps watching for the next loop, and the caller for a loop's last block,
// before sleeping: a step posts a loop every few tens of microseconds, and a sleeping thread's
// wake-up costs a system call on one side and a reschedule on the other. Only a pool with a core
// for each of its threads watches: with more threads than cores, a watching thread would take
// the core of the thread it waits for.
constexpr int32 kSpinChecks = 4096;

// The cores this process may run on: its affinity mask where the system has one (a container
// pinned to a few cores of a large host), else the machine's count (0 when unknown).
unsigned UsableCores() {
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0) return static_cast<unsigned>(CPU_COUNT(&set));
#endif
    return std::thread::hardware_concurrency();
}

// The core count decides only how long a thread waits before it sleeps, never what any loop
// computes or in which order its results are merged.
int32 SpinChecksFor(int32 threads) {
    const unsigned cores = UsableCores();
    return cores != 0 && static_cast<unsigned>(threads) <= cores ? kSpinChecks : 0;
}

// Pauses until `done()` holds or `checks` pauses have passed.
template <class Done>
void Watch(int32 checks, Done done) {
    for (int32 i = 0; i < checks && !done(); ++i) SpinPause();
}
}  // namespace

struct b2ThreadPool::Shared {
    // The loop in hand. Written under `mutex` by the caller while no worker is inside a loop
    // (busy == 0), read by a worker after it registered under the same lock.
    struct Loop {
        int32 itemCount = 0;
        int32 blockSize = 1;
        int32 blockCount = 0;
        b2TaskRange range = nullptr;
        void* context = nullptr;
    };

    int32 workerCount = 1;
    int32 spinChecks = 0;  // pauses a thread watches before it sleeps (SpinChecksFor)
    std::mutex mutex;
    std::condition_variable wake;      // workers wait here for a new loop or for stop
    std::condition_variable finished;  // the caller waits here for the loop's end
    // Written under `mutex`; atomic so that a watching thread may read them without it (every
    // decision is taken again under the lock).
    std::atomic<uint64> generation{0};  // loops posted so far
    std::atomic<bool> stop{false};
    std::atomic<int32> busy{0};  // workers inside the current loop
    Loop loop;                   // under mutex
    std::atomic<int32> nextBlock{0};
    std::atomic<int32> pendingBlocks{0};
    std::vector<std::thread> threads;

    // Takes blocks until none is left; returns after the last block it ran.
    void RunBlocks(const Loop& l) {
        for (;;) {
            const int32 k = nextBlock.fetch_add(1, std::memory_order_relaxed);
            if (k >= l.blockCount) return;
            const int32 begin = k * l.blockSize;
            const int32 end = std::min(begin + l.blockSize, l.itemCount);
            l.range(begin, end, l.context);
            // acq_rel: the block's writes are visible to whoever sees the count reach zero.
            if (pendingBlocks.fetch_sub(1, std::memory_order_acq_rel) == 1) {
                const std::lock_guard<std::mutex> lock(mutex);
                finished.notify_one();
            }
        }
    }

    void WorkerMain() {
        uint64 seen = 0;
        for (;;) {
            const auto posted = [&] { return stop.load() || generation.load() != seen; };
            Watch(spinChecks, posted);
            std::unique_lock<std::mutex> lock(mutex);
            wake.wait(lock, posted);
            if (stop.load()) return;
            seen = generation.load();
            const Loop l = loop;
            busy.fetch_add(1);
            lock.unlock();
            RunBlocks(l);
            lock.lock();
            if (busy.fetch_sub(1) == 1) finished.notify_one();
        }
    }
};

b2ThreadPool::b2ThreadPool(int32 workerCount) : m_shared(std::make_unique<Shared>()) {
    m_shared->workerCount = std::clamp(workerCount, int32{1}, kMaxWorkers);
    m_shared->spinChecks = SpinChecksFor(m_shared->workerCount);
    m_shared->threads.reserve(static_cast<size_t>(m_shared->workerCount - 1));
    for (int32 i = 1; i < m_shared->workerCount; ++i)
        m_shared->threads.emplace_back([s = m_shared.get()] { s->WorkerMain(); });
}

b2ThreadPool::~b2ThreadPool() {
    {
        const std::lock_guard<std::mutex> lock(m_shared->mutex);
        m_shared->stop.store(true);
    }
    m_shared->wake.notify_all();
    for (std::thread& t : m_shared->threads) t.join();
}

int32 b2ThreadPool::GetWorkerCount() const noexcept { return m_shared->workerCount; }

void b2ThreadPool::ParallelFor(int32 itemCount, int32 blockSize, b2TaskRange range, void* context) {
    if (itemCount <= 0) return;
    blockSize = std::max(blockSize, int32{1});
    const int32 blockCount = 1 + (itemCount - 1) / blockSize;
    Shared& s = *m_shared;
    if (s.threads.empty() || blockCount == 1) {
        range(0, itemCount, context);
        return;
    }
    Shared::Loop l;
    l.itemCount = itemCount;
    l.blockSize = blockSize;
    l.blockCount = blockCount;
    l.range = range;
    l.context = context;
    {
        // A worker that woke too late for the previous loop may still be leaving it (it took
        // no block, but it reads the block counter): let it out before the counters change.
        std::unique_lock<std::mutex> lock(s.mutex);
        s.finished.wait(lock, [&] { return s.busy.load() == 0; });
        s.loop = l;
        s.nextBlock.store(0, std::memory_order_relaxed);
        s.pendingBlocks.store(blockCount, std::memory_order_relaxed);
        s.generation.fetch_add(1);
    }
    s.wake.notify_all();
    s.RunBlocks(l);
    // Every block done, and no worker still reading this loop, before the caller goes on (and
    // before the next loop may overwrite it). The last blocks usually end within microseconds.
    const auto ended = [&] { return s.pendingBlocks.load(std::memory_order_acquire) == 0 && s.busy.load() == 0; };
    Watch(s.spinChecks, ended);
    std::unique_lock<std::mutex> lock(s.mutex);
    s.finished.wait(lock, ended);
}

}  // namespace lockbox
