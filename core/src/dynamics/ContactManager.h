#pragma once
// b2ContactManager (Box2D 2.2.1 b2ContactManager.h): owns the broad phase and the contacts,
// turns broad-phase pairs into contacts and keeps their manifolds up to date.

#include <vector>

#include "Engine.h"
#include "dynamics/Pool.h"
#include "dynamics/TimeStep.h"
#include "lockbox/collision/BroadPhase.h"
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/Profile.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

class b2ContactFilter;
class b2ContactListener;
class b2Fixture;
class b2TaskSystem;

/// Contact bookkeeping for one world.
class core_detail::Engine::ContactManager {
public:
    /// fixtures is the world's fixture pool: broad-phase user data are fixture ids.
    explicit ContactManager(b2Pool<b2Fixture>* fixtures);
    ContactManager(const ContactManager&) = delete;
    ContactManager& operator=(const ContactManager&) = delete;

    /// Broad-phase callback: creates a contact for a new overlapping pair (after the body,
    /// joint and filter checks). Keys are b2FixtureProxy::MakeKey values.
    void AddPair(uint64 proxyUserDataA, uint64 proxyUserDataB);
    /// Reports new pairs of moved proxies to AddPair.
    void FindNewContacts();
    /// Destroys a contact (EndContact first when it was touching).
    void Destroy(b2Contact* c);
    /// Re-filters flagged contacts, drops contacts whose fat AABBs separated, and updates the
    /// manifolds of contacts with an awake, non-static body. With a task system of more than
    /// one worker and at least minParallelContacts contacts, the manifolds are evaluated in
    /// parallel first; everything else (and every listener call) then happens in list order,
    /// exactly as with one worker.
    void Collide(b2TaskSystem* tasks, int32 minParallelContacts);

    /// The contact with a given id (nullptr when free).
    b2Contact* GetContact(int32 id) noexcept { return m_contacts.Get(id); }
    /// The contact pool (ids and free list).
    const b2Pool<b2Contact>& GetPool() const noexcept { return m_contacts; }
    /// Snapshot restore: the contact pool's slot layout (see b2Pool::RestoreLayout).
    template <class Make>
    void RestoreContactLayout(const std::vector<uint8>& live, const std::vector<int32>& freeList, Make make) {
        m_contacts.RestoreLayout(live, freeList, make);
    }

    b2BroadPhase m_broadPhase;
    b2Contact* m_contactList = nullptr;
    int32 m_contactCount = 0;
    b2ContactFilter* m_contactFilter = nullptr;      ///< nullptr: the default rule
    b2ContactListener* m_contactListener = nullptr;  ///< nullptr: no events, no overhead
    b2Profile* m_profile = nullptr;                  ///< counters of the current step (owned by the world)

private:
    /// A manifold evaluated ahead of the list walk (possibly on a worker thread).
    struct Evaluated {
        b2Manifold manifold;
        uint64 saturations = 0;  ///< fixed-point saturations of the evaluation
        bool sensor = false;     ///< the pair was a sensor pair when evaluated
        bool touching = false;
    };

    bool ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB);
    /// Evaluates, on the task system, the contacts the list walk will update unless a listener
    /// changes their filtering first: m_evaluatedContacts in list order, m_evaluated beside.
    void EvaluateAhead(b2TaskSystem& tasks);
    static void EvaluateRange(int32 begin, int32 end, void* self);

    // Narrow-phase scratch of the parallel path (grown, never shrunk; not state).
    std::vector<b2Contact*> m_evaluatedContacts;
    std::vector<Evaluated> m_evaluated;

    b2Pool<b2Fixture>* m_fixtures;
    b2Pool<b2Contact> m_contacts;
};

using b2ContactManager = core_detail::Engine::ContactManager;

}  // namespace lockbox
