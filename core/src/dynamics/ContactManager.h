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
    /// Reports new pairs of moved proxies to AddPair. With a task system of more than one
    /// worker, the workers run the broad-phase's tree queries when at least minParallel
    /// proxies moved, and screen the pairs when there are at least minParallel of them (every
    /// rule before the user's filter reads only the world as it is); the contacts are then made
    /// in pair order on the calling thread, so the result is the one-worker result.
    void FindNewContacts(b2TaskSystem* tasks = nullptr, int32 minParallel = 0);
    /// Destroys a contact (EndContact first when it was touching).
    void Destroy(b2Contact* c);
    /// Adds `change` to both bodies' b2Body::m_toiContacts when the linked contact `c` carries
    /// b2Contact::m_toiBodies (made, destroyed or restored: +1, -1, +1).
    static void CountToiMark(const b2Contact& c, int32 change) noexcept;
    /// Re-filters flagged contacts, drops contacts whose fat AABBs separated, and updates the
    /// manifolds of contacts with an awake, non-static body. With a task system of more than
    /// one worker and at least minParallelContacts contacts, the workers take the contacts'
    /// own work; what reaches outside a contact (destroying it, waking its bodies, every
    /// listener call) still happens in list order, so the result is the one-worker result.
    void Collide(b2TaskSystem* tasks, int32 minParallelContacts);

    /// Calls f(b2Contact&) for every contact in slots [begin, end), in slot order (memory
    /// order); slots are below SlotCount().
    template <class F>
    void ForEachInSlots(int32 begin, int32 end, F f) {
        m_contacts.ForEachLiveIn(begin, end, f);
    }
    /// Number of contact slots (live or free).
    int32 SlotCount() const noexcept { return m_contacts.GetCapacity(); }

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

    /// What the last narrow phase on workers without a listener left to the list order, for
    /// tests: inactive contacts that a body woken before them in the list brought into the
    /// walk, and those of woken bodies that the walk had already passed (left as they were).
    struct WokenCounts {
        int32 joined = 0;
        int32 passed = 0;
    };
    WokenCounts m_lastWoken;

private:
    /// A manifold evaluated ahead of the list walk (possibly on a worker thread).
    struct Evaluated {
        b2Manifold manifold;
        uint64 saturations = 0;  ///< fixed-point saturations of the evaluation
        bool sensor = false;     ///< the pair was a sensor pair when evaluated
        bool touching = false;
    };

    /// What the workers' pass left a contact with, for the pass in list order (by contact id).
    enum class Pending : uint8 {
        kDone,      ///< updated, nothing left to do (or a free slot)
        kInactive,  ///< neither body awake and movable: updated only if a body is woken before it
        kQueued,    ///< was inactive, a body was woken before it: the list walk's work, in order
        kWake,      ///< updated; began or stopped touching, so both bodies wake, in order
        kDestroy,   ///< fat AABBs apart: destroyed, in order
        kRefilter   ///< flagged for filtering: the list walk's work, in order
    };
    /// One block of the workers' pass: what it counted.
    struct BlockTally {
        uint64 saturations = 0;
        int32 updated = 0;
        int32 evaluated = 0;
    };

    bool ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB);

    /// A broad-phase pair as fixtures and child indices (a fixture is nullptr when its key names
    /// none).
    struct NewPair {
        b2Fixture* fixtureA = nullptr;
        b2Fixture* fixtureB = nullptr;
        int32 indexA = 0;
        int32 indexB = 0;
    };
    NewPair Resolve(uint64 proxyUserDataA, uint64 proxyUserDataB) const;
    /// The same for a pair of broad-phase proxy ids.
    NewPair Resolve(const b2Pair& pair) const;
    /// AddPair's rules before the user's filter: both fixtures exist on different bodies, the
    /// default filter (when no user filter is set) lets them meet, no contact of theirs exists
    /// and the bodies may collide (types and joints). Reads the world only, so workers may run
    /// it for distinct pairs at once.
    bool Screen(const NewPair& pair) const;
    /// AddPair's rest for a screened pair: the user's filter, the shape rule, the new contact.
    void Take(const NewPair& pair);
    /// One block of FindNewContacts's screening (a b2TaskRange; `self` is the manager).
    static void ScreenRange(int32 begin, int32 end, void* self);
    /// The walk's keep test: the fat AABBs of the contact's two proxies still overlap.
    bool FatAABBsOverlap(const b2Contact& c) const;
    /// The list walk's work on one contact (2.2.1's loop body): re-filter it when flagged, skip
    /// it unless a body is awake and movable, destroy it when the fat AABBs separated, else
    /// update it (from `evaluated` when it was evaluated ahead). Returns false when it skipped
    /// the contact as inactive.
    bool CollideInOrder(b2Contact* c, const Evaluated* evaluated);
    /// Evaluates, on the task system, the contacts the list walk will update unless a listener
    /// changes their filtering first: m_evaluatedContacts in list order, m_evaluated beside.
    void EvaluateAhead(b2TaskSystem& tasks);
    static void EvaluateRange(int32 begin, int32 end, void* self);
    /// Collide for a world without a contact listener: the workers update in place, by slot,
    /// every contact that is active and still overlapping; what is left is then done in list
    /// order (by list key), as the walk would meet it.
    void UpdateOnWorkers(b2TaskSystem& tasks);
    static void UpdateSlots(int32 begin, int32 end, void* self);
    /// Min-heap order on list keys (distinct, so no ties): the head comes out first.
    static bool LaterInList(const b2Contact* a, const b2Contact* b);
    /// After an operation at list key `key`: if `body` was asleep before it and is awake now,
    /// its inactive contacts after that key join the walk.
    void QueueWoken(const b2Body* body, bool wasAwake, int64_t key);

    // Narrow-phase scratch of the parallel paths (grown, never shrunk; not state).
    std::vector<b2Contact*> m_evaluatedContacts;
    std::vector<Evaluated> m_evaluated;
    std::vector<Pending> m_pending;
    std::vector<BlockTally> m_tallies;
    std::vector<b2Contact*> m_inOrder;  ///< min-heap on list key
    // Pair-screening scratch of the parallel path (grown, never shrunk; not state).
    const std::vector<b2Pair>* m_screenPairs = nullptr;  ///< the broad-phase's pairs being screened
    std::vector<uint8> m_screened;                       ///< per pair: 1 when Screen passed it

    b2Pool<b2Fixture>* m_fixtures;
    b2Pool<b2Contact> m_contacts;
};

using b2ContactManager = core_detail::Engine::ContactManager;

}  // namespace lockbox
