#pragma once
// The walk that makes an island: 2.2.1's depth-first search of the constraint graph from a
// seed, whose order is the island's solve order. The one-worker search (WorldSolve.cpp) and the
// workers' walks (IslandSearch.cpp) differ only in where the island goes and in how a static
// body, which islands share, is marked; a sink says both.
//
// A sink has:
//   void Body(b2Body*)          every body of the island, in walk order (static ones included)
//   void Static(b2Body*)        then, for a static body, this too
//   void Contact(b2Contact*)    every contact of the island, in walk order
//   void Joint(b2Joint*)        every joint of the island, in walk order
//   bool Meet(b2Body&)          true the first time the island reaches the body, which it marks
// Non-static bodies are marked by their island flag (Meet's usual mark), and woken; each is
// left with its scan mark (b2Body::e_scannedFlag), which the caller clears with ClearScanMarks
// once the island is complete.

#include <span>
#include <vector>

#include "dynamics/JointGraph.h"
#include "dynamics/WorldState.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"

namespace lockbox {

template <class Sink>
void core_detail::Engine::World::WalkIsland(b2Body* seed, const JointGraph& joints, std::vector<b2Body*>& stack,
                                            Sink& sink) {
    stack.clear();
    stack.push_back(seed);
    seed->m_flags |= b2Body::e_islandFlag;
    while (!stack.empty()) {
        b2Body* b = stack.back();
        stack.pop_back();
        sink.Body(b);
        // Islands do not propagate across static bodies.
        if (b->m_type == b2_staticBody) {
            sink.Static(b);
            continue;
        }
        b->SetAwake(true);
        b->m_flags |= b2Body::e_scannedFlag;

        for (b2ContactEdge* ce = b->m_contactList; ce; ce = ce->next) {
            // The graph lies scattered in memory: request the next edge's line while this one
            // is looked at (a hint only).
            if (ce->next != nullptr) __builtin_prefetch(ce->next);
            b2Contact* contact = ce->contact;
            if (contact->m_flags & b2Contact::e_islandFlag) continue;
            if (!contact->IsEnabled() || !contact->IsTouching()) continue;
            LOCKBOX_ASSERT(contact->IsSensorPair() == contact->SensorPairNow(), "stale sensor mark");
            if (contact->IsSensorPair()) continue;
            sink.Contact(contact);
            contact->m_flags |= b2Contact::e_islandFlag;
            b2Body* other = ce->other;
            if (!sink.Meet(*other)) continue;
            stack.push_back(other);
            if (other->m_contactList != nullptr) __builtin_prefetch(other->m_contactList);
            joints.Prefetch(*other);
        }

        // The joint list's edges, read from the graph's copy (one array, not a chain through
        // the joints).
        LOCKBOX_ASSERT(joints.Matches(*b), "the island search's joint graph is stale: a joint list changed unmarked");
        for (const JointGraph::Edge& edge : joints.Of(*b)) {
            b2Body* other = edge.other;
            // A joint between two bodies without mass (kinematic-static, kinematic-kinematic)
            // can change nothing: it costs nothing either. Tested first, on the body types
            // alone: such a joint may lead into another island, whose flags a worker's walk
            // must not read.
            if (b->m_type != b2_dynamicBody && other->m_type != b2_dynamicBody) continue;
            // A joint is taken from the first of its bodies to be scanned (a static body never
            // is), so one whose other body was scanned is in the island already. This reads
            // only the other body, which the search reads anyway, not the joint.
            if (other->m_flags & b2Body::e_scannedFlag) continue;
            // Don't simulate joints connected to inactive bodies.
            if (!other->IsActive()) continue;
            sink.Joint(edge.joint);
            if (!sink.Meet(*other)) continue;
            stack.push_back(other);
            joints.Prefetch(*other);
        }
    }
}

inline void core_detail::Engine::World::ClearScanMarks(std::span<b2Body* const> island) noexcept {
    // Static bodies never take the mark, and other workers' walks read them meanwhile.
    for (b2Body* b : island) {
        if (b->m_type != b2_staticBody) b->m_flags &= ~b2Body::e_scannedFlag;
    }
}

}  // namespace lockbox
