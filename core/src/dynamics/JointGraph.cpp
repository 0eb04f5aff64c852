// The island search's copy of the joint lists (JointGraph.h).
#include "dynamics/JointGraph.h"

namespace lockbox {

void core_detail::Engine::JointGraph::Refresh(const b2Body* bodyList, int32 slots) {
    if (m_current) return;
    m_current = true;
    m_ranges.assign(static_cast<size_t>(slots), Range{});
    m_edges.clear();
    // One pass: each body's edges are appended together, so its range is contiguous.
    for (const b2Body* b = bodyList; b != nullptr; b = b->m_next) {
        Range& range = m_ranges[static_cast<size_t>(b->m_id)];
        range.begin = static_cast<int32>(m_edges.size());
        for (const b2JointEdge* je = b->m_jointList; je != nullptr; je = je->next)
            m_edges.push_back({je->other, je->joint});
        range.end = static_cast<int32>(m_edges.size());
    }
    // No joint: every body's edges are the empty range, without a table to look in.
    if (m_edges.empty()) m_ranges.clear();
}

bool core_detail::Engine::JointGraph::Matches(const b2Body& body) const noexcept {
    const std::span<const Edge> edges = Of(body);
    size_t i = 0;
    for (const b2JointEdge* je = body.m_jointList; je != nullptr; je = je->next, ++i) {
        if (i == edges.size() || edges[i].other != je->other || edges[i].joint != je->joint) return false;
    }
    return i == edges.size();
}

}  // namespace lockbox
