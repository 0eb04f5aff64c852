#pragma once
// b2Pool: the storage of bodies, fixtures and contacts.
//
// Objects live in chunked blocks that are never moved or freed while the pool lives, so a
// pointer to a slot stays valid until that slot is destroyed (ARCHITECTURE §4: the pointer API
// is a facade over slots). Every slot has a small int32 id: its index. Free slots are reused in
// LIFO order from an explicit stack of ids, so the id sequence depends only on the sequence of
// creations and destructions, never on addresses. A part of the engine (Engine.h), so that it
// may construct the core's objects, whose constructors are private.

#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "Engine.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

/// Null object id.
inline constexpr int32 b2_nullId = -1;

/// A pool of T with stable addresses and LIFO id reuse. Not thread-safe.
template <typename T, int32 kBlockSize>
class core_detail::Engine::Pool {
public:
    Pool() = default;
    Pool(const Pool&) = delete;
    Pool& operator=(const Pool&) = delete;
    ~Pool() { Clear(); }

    /// Constructs a T in a free slot (the most recently freed one first, else a new slot) and
    /// returns its id. The object's address is Get(id) and stays fixed until Destroy(id).
    template <typename... Args>
    int32 Create(Args&&... args) {
        int32 id;
        if (!m_free.empty()) {
            id = m_free.back();
            m_free.pop_back();
        } else {
            id = static_cast<int32>(m_live.size());
            if (id % kBlockSize == 0) m_blocks.push_back(std::make_unique<Slot[]>(kBlockSize));
            m_live.push_back(0);
        }
        ::new (static_cast<void*>(SlotAt(id))) T(std::forward<Args>(args)...);
        m_live[static_cast<size_t>(id)] = 1;
        ++m_count;
        return id;
    }

    /// Destroys the object in slot id and pushes id on the free stack. id must be live.
    void Destroy(int32 id) {
        if (!IsLive(id)) return;
        Get(id)->~T();
        m_live[static_cast<size_t>(id)] = 0;
        m_free.push_back(id);
        --m_count;
    }

    /// The object in slot id, or nullptr when the slot is free or out of range.
    T* Get(int32 id) noexcept { return IsLive(id) ? std::launder(reinterpret_cast<T*>(SlotAt(id))) : nullptr; }
    const T* Get(int32 id) const noexcept {
        return IsLive(id) ? std::launder(reinterpret_cast<const T*>(SlotAt(id))) : nullptr;
    }

    /// True when slot id holds an object.
    bool IsLive(int32 id) const noexcept {
        return id >= 0 && static_cast<size_t>(id) < m_live.size() && m_live[static_cast<size_t>(id)] != 0;
    }

    /// Number of live objects.
    int32 GetCount() const noexcept { return m_count; }
    /// Number of slots ever used (live + free); ids are below this.
    int32 GetCapacity() const noexcept { return static_cast<int32>(m_live.size()); }
    /// The free-slot stack, bottom first (the next Create takes the back).
    const std::vector<int32>& GetFreeList() const noexcept { return m_free; }
    /// One flag per slot id, 1 for live (the layout RestoreLayout takes).
    const std::vector<uint8>& GetLiveFlags() const noexcept { return m_live; }

    /// Calls f(T&) for every live object in slot order: memory order, for walks whose order
    /// does not matter (clearing per-step flags), which a linked list would take in cache misses.
    template <class F>
    void ForEachLive(F f) {
        ForEachLiveIn(0, GetCapacity(), f);
    }
    /// ForEachLive over slots [begin, end) only (0 <= begin <= end <= GetCapacity()).
    template <class F>
    void ForEachLiveIn(int32 begin, int32 end, F f) {
        for (int32 id = begin; id < end; ++id) {
            if (m_live[static_cast<size_t>(id)] != 0) f(*std::launder(reinterpret_cast<T*>(SlotAt(id))));
        }
    }

    /// Snapshot restore: makes the slot layout exactly `live` (one flag per id; its size is the
    /// new capacity) with the free stack `freeList`. Objects in slots that stay live keep their
    /// address; slots that become free are destroyed; newly live slots are built by
    /// make(void* slot, int32 id), which must placement-new a T there.
    template <class Make>
    void RestoreLayout(const std::vector<uint8>& live, const std::vector<int32>& freeList, Make make) {
        const int32 capacity = static_cast<int32>(live.size());
        for (int32 id = 0; id < GetCapacity(); ++id) {
            if (IsLive(id) && (id >= capacity || live[static_cast<size_t>(id)] == 0)) {
                Get(id)->~T();
                m_live[static_cast<size_t>(id)] = 0;
            }
        }
        m_live.resize(static_cast<size_t>(capacity), 0);
        // Blocks past the new capacity hold no live object now: free them.
        m_blocks.resize(static_cast<size_t>((capacity + kBlockSize - 1) / kBlockSize));
        for (auto& block : m_blocks) {
            if (!block) block = std::make_unique<Slot[]>(kBlockSize);
        }
        m_count = 0;
        for (int32 id = 0; id < capacity; ++id) {
            if (live[static_cast<size_t>(id)] == 0) continue;
            if (m_live[static_cast<size_t>(id)] == 0) {
                make(static_cast<void*>(SlotAt(id)), id);
                m_live[static_cast<size_t>(id)] = 1;
            }
            ++m_count;
        }
        m_free = freeList;
    }

    /// Destroys every object and forgets all slots.
    void Clear() {
        for (int32 id = 0; id < GetCapacity(); ++id) {
            if (IsLive(id)) Get(id)->~T();
        }
        m_blocks.clear();
        m_live.clear();
        m_free.clear();
        m_count = 0;
    }

private:
    struct Slot {
        alignas(T) std::byte bytes[sizeof(T)];
    };
    std::byte* SlotAt(int32 id) const noexcept {
        return m_blocks[static_cast<size_t>(id / kBlockSize)][static_cast<size_t>(id % kBlockSize)].bytes;
    }

    std::vector<std::unique_ptr<Slot[]>> m_blocks;
    std::vector<uint8> m_live;
    std::vector<int32> m_free;
    int32 m_count = 0;
};

template <typename T, int32 kBlockSize = 64>
using b2Pool = core_detail::Engine::Pool<T, kBlockSize>;

}  // namespace lockbox
