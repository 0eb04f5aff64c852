#pragma once
// b2ScratchSet: one set of buffers per block of a parallel loop that runs at the same time as
// others. A block takes a free one for as long as it runs (a lease), so that buffers are made
// once per worker and reused, whatever thread a block lands on.

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "lockbox/common/Settings.h"

namespace lockbox {

template <class T>
class b2ScratchSet {
    struct Slot {
        T value;
        // A word, not a bool: byte-sized compare-exchange needs libatomic on some targets
        // (riscv64 at -O0).
        std::atomic<uint32_t> busy{0};
    };

public:
    /// A scratch held by one block; given back when the lease ends.
    class Lease {
    public:
        explicit Lease(Slot& slot) noexcept : m_slot(slot) {}
        ~Lease() { m_slot.busy.store(0, std::memory_order_release); }
        Lease(const Lease&) = delete;
        Lease& operator=(const Lease&) = delete;
        T& operator*() const noexcept { return m_slot.value; }
        T* operator->() const noexcept { return &m_slot.value; }

    private:
        Slot& m_slot;
    };

    /// Makes sure there are at least `count` scratches (the task system's worker count). Not
    /// while a loop runs.
    void Reserve(int32 count) {
        while (m_slots.size() < static_cast<size_t>(count)) m_slots.push_back(std::make_unique<Slot>());
    }

    /// Takes a free scratch. A task system runs at most GetWorkerCount() blocks at once and
    /// Reserve made that many, so one is free; a job system that runs more waits here.
    Lease Acquire() noexcept {
        for (;;) {
            for (const std::unique_ptr<Slot>& s : m_slots) {
                uint32_t expected = 0;
                if (s->busy.compare_exchange_strong(expected, 1, std::memory_order_acquire)) return Lease(*s);
            }
        }
    }

    /// Calls f(T&) on every scratch, in the order they were made. Not while a loop runs.
    template <class F>
    void ForEach(F f) {
        for (const std::unique_ptr<Slot>& s : m_slots) f(s->value);
    }
    /// The first scratch (Reserve(1) or more first), for work done on the calling thread alone.
    T& Front() noexcept { return m_slots.front()->value; }

private:
    std::vector<std::unique_ptr<Slot>> m_slots;
};

}  // namespace lockbox
