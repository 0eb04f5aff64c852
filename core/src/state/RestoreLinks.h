#pragma once
// Internal to the restores (SnapshotApply.cpp, WorldFrame.cpp): relinking restored objects.
// Both restores install bodies, contacts and joints in world-list order; each body's contact
// and joint edges are in that order too (StateWalk.h), so appending as a list is rebuilt
// rebuilds the edges while the object is in cache.

#include <vector>

#include "Engine.h"
#include "dynamics/ContactManager.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox::state_detail {

/// A fixture as a restored contact needs it: the world's fixture, its body and the body's id.
struct FixtureSlot {
    b2Fixture* fixture = nullptr;
    b2Body* body = nullptr;
    int32 bodyId = -1;
    bool sensor = false;  ///< fixture->IsSensor(), so that linking a contact need not visit the fixture
};

/// Where the contact list being rebuilt stands: its last contact, and the last contact edge of
/// each body (by id; all null before the first contact, every body's list then empty).
struct ContactListTail {
    b2Contact* last = nullptr;
    std::vector<b2ContactEdge*>& edgeTails;
};

}  // namespace lockbox::state_detail

namespace lockbox {

/// The list and edge links the restores write into bodies, contacts and joints.
struct core_detail::Engine::RestoreLinks {
    /// Appends a node at the tail of a doubly linked world list (bodies, contacts, joints).
    template <class T>
    static void AppendToWorldList(T* node, T*& head, T*& tail) {
        node->m_prev = tail;
        node->m_next = nullptr;
        if (tail != nullptr)
            tail->m_next = node;
        else
            head = node;
        tail = node;
    }

    static void LinkRestoredContact(b2Contact* c, int32 fixtureA, int32 indexA, int32 fixtureB, int32 indexB,
                                    const state_detail::FixtureSlot& a, const state_detail::FixtureSlot& b,
                                    b2Contact*& head, state_detail::ContactListTail& tail);
};

}  // namespace lockbox

namespace lockbox::state_detail {

/// Appends a node at the tail of a doubly linked world list (bodies, contacts, joints).
template <class T>
void AppendToWorldList(T* node, T*& head, T*& tail) {
    core_detail::Engine::RestoreLinks::AppendToWorldList(node, head, tail);
}

/// Links an edge (contact or joint) at the tail of a body's list, given the list's current
/// tail.
template <class Edge>
void AppendEdge(Edge* e, Edge*& head, Edge*& tail) {
    e->prev = tail;
    e->next = nullptr;
    if (tail != nullptr)
        tail->next = e;
    else
        head = e;
    tail = e;
}

/// Points contact c at its fixtures (ids and child indices given) and appends it to the world's
/// contact list (head) and to both bodies' edge lists.
inline void LinkRestoredContact(b2Contact* c, int32 fixtureA, int32 indexA, int32 fixtureB, int32 indexB,
                                const FixtureSlot& a, const FixtureSlot& b, b2Contact*& head, ContactListTail& tail) {
    core_detail::Engine::RestoreLinks::LinkRestoredContact(c, fixtureA, indexA, fixtureB, indexB, a, b, head, tail);
}

}  // namespace lockbox::state_detail

namespace lockbox {

inline void core_detail::Engine::RestoreLinks::LinkRestoredContact(b2Contact* c, int32 fixtureA, int32 indexA,
                                                                   int32 fixtureB, int32 indexB,
                                                                   const state_detail::FixtureSlot& a,
                                                                   const state_detail::FixtureSlot& b, b2Contact*& head,
                                                                   state_detail::ContactListTail& tail) {
    c->m_fixtureA = a.fixture;
    c->m_fixtureB = b.fixture;
    c->m_fixtureIdA = fixtureA;
    c->m_fixtureIdB = fixtureB;
    c->m_indexA = indexA;
    c->m_indexB = indexB;
    c->m_sensor = a.sensor || b.sensor;
    c->m_toiBodies = b2Contact::ToiBodies(*a.body, *b.body);
    c->m_nodeA = b2ContactEdge{b.body, c, nullptr, nullptr};
    c->m_nodeB = b2ContactEdge{a.body, c, nullptr, nullptr};
    b2ContactManager::CountToiMark(*c, 1);
    // Appended at the tail: one more than the contact before it (b2Contact::m_listKey).
    c->m_listKey = tail.last != nullptr ? tail.last->m_listKey + 1 : 0;
    AppendToWorldList(c, head, tail.last);
    state_detail::AppendEdge(&c->m_nodeA, a.body->m_contactList, tail.edgeTails[static_cast<size_t>(a.bodyId)]);
    state_detail::AppendEdge(&c->m_nodeB, b.body->m_contactList, tail.edgeTails[static_cast<size_t>(b.bodyId)]);
}

}  // namespace lockbox
