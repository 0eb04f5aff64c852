#pragma once
// Internal to the restores (SnapshotApply.cpp, WorldFrame.cpp): a restored contact's links.
// Both restores install contacts in world-list order; each body's contact edges are in that
// order too (StateWalk.h), so appending as the list is rebuilt rebuilds the edges while the
// contact is in cache.

#include <vector>

#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox::state_detail {

/// A fixture as a restored contact needs it: the world's fixture, its body and the body's id.
struct FixtureSlot {
    b2Fixture* fixture = nullptr;
    b2Body* body = nullptr;
    int32 bodyId = -1;
};

/// Where the contact list being rebuilt stands: its last contact, and the last contact edge of
/// each body (by id; all null before the first contact, every body's list then empty).
struct ContactListTail {
    b2Contact* last = nullptr;
    std::vector<b2ContactEdge*>& edgeTails;
};

inline void AppendContactEdge(b2ContactEdge* edge, b2Body* body, b2ContactEdge*& tail) {
    edge->prev = tail;
    edge->next = nullptr;
    if (tail != nullptr) tail->next = edge;
    else body->m_contactList = edge;
    tail = edge;
}

/// Points contact c at its fixtures (ids and child indices given) and appends it to the world's
/// contact list (head) and to both bodies' edge lists.
inline void LinkRestoredContact(b2Contact* c, int32 fixtureA, int32 indexA, int32 fixtureB, int32 indexB,
                                const FixtureSlot& a, const FixtureSlot& b, b2Contact*& head, ContactListTail& tail) {
    c->m_fixtureA = a.fixture;
    c->m_fixtureB = b.fixture;
    c->m_fixtureIdA = fixtureA;
    c->m_fixtureIdB = fixtureB;
    c->m_indexA = indexA;
    c->m_indexB = indexB;
    c->m_nodeA = b2ContactEdge{b.body, c, nullptr, nullptr};
    c->m_nodeB = b2ContactEdge{a.body, c, nullptr, nullptr};
    c->m_prev = tail.last;
    c->m_next = nullptr;
    if (tail.last != nullptr) tail.last->m_next = c;
    else head = c;
    tail.last = c;
    AppendContactEdge(&c->m_nodeA, a.body, tail.edgeTails[static_cast<size_t>(a.bodyId)]);
    AppendContactEdge(&c->m_nodeB, b.body, tail.edgeTails[static_cast<size_t>(b.bodyId)]);
}

}  // namespace lockbox::state_detail
