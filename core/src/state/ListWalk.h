#pragma once
// Internal to the state code: how the walks over the world's linked lists keep the memory
// system busy. List order is not memory order, so each node would be a cache miss; these
// request nodes (and what they point to) ahead of the record being written.

#include <cstddef>

#include "dynamics/Access.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox::state_detail {

/// Starts loading every cache line of an object.
template <class T>
inline void PrefetchObject(const T* node) noexcept {
    if (node == nullptr) return;
    const char* p = reinterpret_cast<const char*>(node);
    for (size_t line = 0; line < sizeof(T); line += 64) __builtin_prefetch(p + line);
}

/// Starts loading `bytes` bytes from p (objects known only by a base type, such as shapes).
inline void PrefetchBytes(const void* p, size_t bytes) noexcept {
    if (p == nullptr) return;
    const char* c = static_cast<const char*>(p);
    for (size_t line = 0; line < bytes; line += 64) __builtin_prefetch(c + line);
}

/// A contact: only the part the state walks read (everything before the graph edges, which
/// follow the flags in b2Contact), every cache line it touches.
inline void PrefetchObject(const b2Contact* c) noexcept {
    if (c == nullptr) return;
    const char* first = reinterpret_cast<const char*>(c);
    const char* last = first + core_detail::Engine::Contacts::WalkedBytes(*c) - 1;
    for (const char* p = first; p < last; p += 64) __builtin_prefetch(p);
    __builtin_prefetch(last);
}

/// Bytes of the largest shape the walks read whole (a polygon of 8: about 170 bytes).
inline constexpr size_t kShapePrefetchBytes = 192;

/// Distance (in list nodes) at which WalkList requests all of a node's cache lines. List
/// order is not memory order, so every line of a node is a miss unless requested early. The
/// m_next chase itself stays one miss per node (a chain cannot be requested ahead); this
/// brings in the node's other lines, which the record reads, in the shadow of that chase.
inline constexpr int kPrefetchDistance = 4;

/// Calls visit(node) on every node of a world list in order, with the node kPrefetchDistance
/// ahead being loaded meanwhile, and touch(node) called two nodes ahead (to prefetch what a
/// node points to once the node itself has arrived).
template <class T, class Visit, class Touch>
void WalkList(const T* head, Visit visit, Touch touch) {
    const T* ahead = head;
    for (int i = 0; i < kPrefetchDistance && ahead != nullptr; ++i) {
        PrefetchObject(ahead);
        ahead = ahead->GetNext();
    }
    const T* near = head != nullptr ? head->GetNext() : nullptr;
    if (near != nullptr) near = near->GetNext();
    for (const T* node = head; node != nullptr; node = node->GetNext()) {
        if (ahead != nullptr) {
            PrefetchObject(ahead);
            ahead = ahead->GetNext();
        }
        if (near != nullptr) {
            touch(near);
            near = near->GetNext();
        }
        visit(*node);
    }
}

}  // namespace lockbox::state_detail
