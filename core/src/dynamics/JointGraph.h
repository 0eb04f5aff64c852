#pragma once
// Each body's joint edges, copied into one array in the order of the body's joint list. The
// island search reads a body's (other body, joint) pairs from there instead of following the
// list: its edges live in the joints, one cache miss each, and each miss must land before the
// next edge's address is known. In a large jointed island that chain was three quarters of the
// search. The copy is derived from the joint lists, never state, and gives the search the very
// order of the lists; it is rebuilt by the first search after a joint is made or destroyed or
// the world's structure is restored.

#include <span>
#include <vector>

#include "Engine.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/joints/Joint.h"

namespace lockbox {

class core_detail::Engine::JointGraph {
public:
    struct Edge {
        b2Body* other;
        b2Joint* joint;
    };

    /// The joint lists changed: the next Refresh rebuilds.
    void Invalidate() noexcept { m_current = false; }

    /// Rebuilds the copy from the joint lists of the bodies in `bodyList` (slot ids below
    /// `slots`) if they changed since it was made. Single-threaded; searches only read.
    void Refresh(const b2Body* bodyList, int32 slots);

    /// The body's edges, in its joint list's order (empty for a body made since the copy,
    /// which has no joint: making one would have invalidated it).
    std::span<const Edge> Of(const b2Body& body) const noexcept {
        const auto id = static_cast<size_t>(body.m_id);
        if (id >= m_ranges.size()) return {};
        const Range range = m_ranges[id];
        return {m_edges.data() + range.begin, m_edges.data() + range.end};
    }

    /// Asks for the body's edges ahead of its search (a hint only).
    void Prefetch(const b2Body& body) const noexcept {
        const auto id = static_cast<size_t>(body.m_id);
        if (id < m_ranges.size()) __builtin_prefetch(m_edges.data() + m_ranges[id].begin);
    }

    /// Whether the copy of the body's edges equals its joint list (checked builds assert it).
    bool Matches(const b2Body& body) const noexcept;

private:
    struct Range {
        int32 begin = 0, end = 0;
    };
    bool m_current = false;
    std::vector<Range> m_ranges;  ///< by body slot id: where the body's edges lie in m_edges
    std::vector<Edge> m_edges;
};

}  // namespace lockbox
