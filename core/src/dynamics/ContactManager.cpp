// b2ContactManager: pairs to contacts, contact destruction and the narrow-phase pass.
#include "dynamics/ContactManager.h"

#include <algorithm>
#include <utility>

#include "dynamics/contacts/ContactRules.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {

namespace {
// The manual's default rule, used when no filter is registered (no virtual call needed).
b2ContactFilter g_defaultFilter;
}  // namespace

b2ContactManager::ContactManager(b2Pool<b2Fixture>* fixtures) : m_fixtures(fixtures) {}

bool b2ContactManager::ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB) {
    b2ContactFilter* filter = m_contactFilter ? m_contactFilter : &g_defaultFilter;
    return filter->ShouldCollide(fixtureA, fixtureB);
}

b2ContactManager::NewPair b2ContactManager::Resolve(uint64 proxyUserDataA, uint64 proxyUserDataB) const {
    NewPair pair;
    pair.fixtureA = m_fixtures->Get(b2FixtureProxy::KeyFixture(proxyUserDataA));
    pair.fixtureB = m_fixtures->Get(b2FixtureProxy::KeyFixture(proxyUserDataB));
    pair.indexA = b2FixtureProxy::KeyChild(proxyUserDataA);
    pair.indexB = b2FixtureProxy::KeyChild(proxyUserDataB);
    return pair;
}

bool b2ContactManager::Screen(const NewPair& pair) const {
    b2Fixture* fixtureA = pair.fixtureA;
    b2Fixture* fixtureB = pair.fixtureB;
    if (fixtureA == nullptr || fixtureB == nullptr) return false;
    const b2Body* bodyA = fixtureA->GetBody();
    const b2Body* bodyB = fixtureB->GetBody();

    // Fixtures on the same body never collide.
    if (bodyA == bodyB) return false;

    // The default filter is a pure test of data already loaded: without a user filter it goes
    // first, before the walks of the contact and joint lists (a jointed grid reports thousands
    // of pairs a step that it rejects). The outcome is the same as in 2.2.1's order.
    if (m_contactFilter == nullptr && !g_defaultFilter.ShouldCollide(fixtureA, fixtureB)) return false;

    // Does a contact already exist? (Walk B's edges, newest first, as 2.2.1.)
    for (const b2ContactEdge* edge = bodyB->m_contactList; edge; edge = edge->next) {
        if (edge->other != bodyA) continue;
        const b2Contact* c = edge->contact;
        const b2Fixture* fA = c->GetFixtureA();
        const b2Fixture* fB = c->GetFixtureB();
        const int32 iA = c->GetChildIndexA();
        const int32 iB = c->GetChildIndexB();
        if (fA == fixtureA && fB == fixtureB && iA == pair.indexA && iB == pair.indexB) return false;
        if (fA == fixtureB && fB == fixtureA && iA == pair.indexB && iB == pair.indexA) return false;
    }

    // Body type rule and joints.
    return bodyB->ShouldCollide(bodyA);
}

void b2ContactManager::AddPair(uint64 proxyUserDataA, uint64 proxyUserDataB) {
    if (m_profile) ++m_profile->pairsFound;
    const NewPair pair = Resolve(proxyUserDataA, proxyUserDataB);
    if (Screen(pair)) Take(pair);
}

void b2ContactManager::Take(const NewPair& pair) {
    b2Fixture* fixtureA = pair.fixtureA;
    b2Fixture* fixtureB = pair.fixtureB;
    int32 indexA = pair.indexA;
    int32 indexB = pair.indexB;
    b2Body* bodyA = fixtureA->GetBody();
    b2Body* bodyB = fixtureB->GetBody();

    // User filtering, after the rules Screen applies, as 2.2.1 orders them.
    if (m_contactFilter != nullptr && !m_contactFilter->ShouldCollide(fixtureA, fixtureB)) return;

    const b2Shape::Type typeA = fixtureA->GetType();
    const b2Shape::Type typeB = fixtureB->GetType();
    if (!core_detail::ShapesCanCollide(typeA, typeB)) return;
    if (core_detail::ShapesNeedSwap(typeA, typeB)) {
        std::swap(fixtureA, fixtureB);
        std::swap(indexA, indexB);
        std::swap(bodyA, bodyB);
    }

    const int32 id = m_contacts.Create(fixtureA, indexA, fixtureB, indexB, 0);
    b2Contact* c = m_contacts.Get(id);
    c->m_id = id;
    if (m_profile) ++m_profile->contactsCreated;

    // Insert at the head of the world list.
    c->m_listKey = m_contactList != nullptr ? m_contactList->m_listKey - 1 : 0;
    c->m_prev = nullptr;
    c->m_next = m_contactList;
    if (m_contactList != nullptr) m_contactList->m_prev = c;
    m_contactList = c;

    // Connect to body A.
    c->m_nodeA.contact = c;
    c->m_nodeA.other = bodyB;
    c->m_nodeA.prev = nullptr;
    c->m_nodeA.next = bodyA->m_contactList;
    if (bodyA->m_contactList != nullptr) bodyA->m_contactList->prev = &c->m_nodeA;
    bodyA->m_contactList = &c->m_nodeA;

    // Connect to body B.
    c->m_nodeB.contact = c;
    c->m_nodeB.other = bodyA;
    c->m_nodeB.prev = nullptr;
    c->m_nodeB.next = bodyB->m_contactList;
    if (bodyB->m_contactList != nullptr) bodyB->m_contactList->prev = &c->m_nodeB;
    bodyB->m_contactList = &c->m_nodeB;
    CountToiMark(*c, 1);

    // 2.2.1 wakes both bodies when a pair forms.
    bodyA->SetAwake(true);
    bodyB->SetAwake(true);

    ++m_contactCount;
}

namespace {
// Pairs per block of the workers' screening.
constexpr int32 kPairsPerBlock = 128;
}  // namespace

b2ContactManager::NewPair b2ContactManager::Resolve(const b2Pair& pair) const {
    const b2DynamicTree& tree = m_broadPhase.GetTree();
    return Resolve(tree.GetUserData(pair.proxyIdA), tree.GetUserData(pair.proxyIdB));
}

void b2ContactManager::ScreenRange(int32 begin, int32 end, void* self) {
    auto* manager = static_cast<b2ContactManager*>(self);
    const std::vector<b2Pair>& pairs = *manager->m_screenPairs;
    for (int32 i = begin; i < end; ++i) {
        const NewPair resolved = manager->Resolve(pairs[static_cast<size_t>(i)]);
        manager->m_screened[static_cast<size_t>(i)] = manager->Screen(resolved) ? 1 : 0;
    }
}

void b2ContactManager::FindNewContacts(b2TaskSystem* tasks, int32 minParallel) {
    if (tasks == nullptr || tasks->GetWorkerCount() <= 1) {
        m_broadPhase.UpdatePairs(this);
        return;
    }
    const bool manyMoves = static_cast<int32>(m_broadPhase.GetMoveBuffer().size()) >= minParallel;
    const std::vector<b2Pair>& pairs =
        manyMoves ? m_broadPhase.CollectPairs([tasks](int32 count, int32 blockSize, b2TaskRange range, void* context) {
            tasks->ParallelFor(count, blockSize, range, context);
        })
                  : m_broadPhase.CollectPairs();
    const auto count = static_cast<int32>(pairs.size());
    if (m_profile) m_profile->pairsFound += count;
    // Distinct pairs are distinct fixture-and-child pairs, so making one pair's contact cannot
    // change another's screening: screening them all first decides what the one-worker order
    // decides. The user's filter and the contacts stay in pair order.
    const bool screenedAhead = count >= b2Max(minParallel, 1);
    if (screenedAhead) {
        m_screenPairs = &pairs;
        m_screened.resize(pairs.size());
        tasks->ParallelFor(count, kPairsPerBlock, &ScreenRange, this);
        m_screenPairs = nullptr;
    }
    for (int32 i = 0; i < count; ++i) {
        if (screenedAhead && m_screened[static_cast<size_t>(i)] == 0) continue;
        const NewPair pair = Resolve(pairs[static_cast<size_t>(i)]);
        if (screenedAhead || Screen(pair)) Take(pair);
    }
}

void b2ContactManager::CountToiMark(const b2Contact& c, int32 change) noexcept {
    if (!c.m_toiBodies) return;
    // Each edge's other body is the contact's other body: node A's is B, node B's is A.
    c.m_nodeA.other->m_toiContacts += change;
    c.m_nodeB.other->m_toiContacts += change;
}

void b2ContactManager::Destroy(b2Contact* c) {
    b2Fixture* fixtureA = c->GetFixtureA();
    b2Fixture* fixtureB = c->GetFixtureB();
    b2Body* bodyA = fixtureA->GetBody();
    b2Body* bodyB = fixtureB->GetBody();

    if (m_contactListener && c->IsTouching()) {
        m_contactListener->EndContact(c);
        if (m_profile) ++m_profile->listenerCallbacks;
    }
    if (m_profile) ++m_profile->contactsDestroyed;

    // Remove from the world list.
    if (c->m_prev) c->m_prev->m_next = c->m_next;
    if (c->m_next) c->m_next->m_prev = c->m_prev;
    if (c == m_contactList) m_contactList = c->m_next;

    // Remove from body A.
    if (c->m_nodeA.prev) c->m_nodeA.prev->next = c->m_nodeA.next;
    if (c->m_nodeA.next) c->m_nodeA.next->prev = c->m_nodeA.prev;
    if (&c->m_nodeA == bodyA->m_contactList) bodyA->m_contactList = c->m_nodeA.next;

    // Remove from body B.
    if (c->m_nodeB.prev) c->m_nodeB.prev->next = c->m_nodeB.next;
    if (c->m_nodeB.next) c->m_nodeB.next->prev = c->m_nodeB.prev;
    if (&c->m_nodeB == bodyB->m_contactList) bodyB->m_contactList = c->m_nodeB.next;
    CountToiMark(*c, -1);

    // A contact that held the bodies apart no longer does: wake them.
    if (c->m_manifold.pointCount > 0) {
        bodyA->SetAwake(true);
        bodyB->SetAwake(true);
    }

    m_contacts.Destroy(c->GetId());
    --m_contactCount;
}

namespace {
// Contacts per block: enough work to amortise taking a block, few enough to balance the load.
constexpr int32 kContactsPerBlock = 32;

// The checks of the list walk before a contact's update, minus the filtering.
bool IsActivePair(const b2Body* bodyA, const b2Body* bodyB) {
    const bool activeA = bodyA->IsAwake() && bodyA->GetType() != b2_staticBody;
    const bool activeB = bodyB->IsAwake() && bodyB->GetType() != b2_staticBody;
    return activeA || activeB;
}
}  // namespace

bool b2ContactManager::FatAABBsOverlap(const b2Contact& c) const {
    const int32 proxyIdA = c.GetFixtureA()->m_proxies[static_cast<size_t>(c.GetChildIndexA())].proxyId;
    const int32 proxyIdB = c.GetFixtureB()->m_proxies[static_cast<size_t>(c.GetChildIndexB())].proxyId;
    return m_broadPhase.TestOverlap(proxyIdA, proxyIdB);
}

void b2ContactManager::EvaluateRange(int32 begin, int32 end, void* self) {
    auto* manager = static_cast<b2ContactManager*>(self);
    for (int32 i = begin; i < end; ++i) {
        b2Contact* c = manager->m_evaluatedContacts[static_cast<size_t>(i)];
        Evaluated& e = manager->m_evaluated[static_cast<size_t>(i)];
        e.saturations = 0;
        const SaturationCapture capture(&e.saturations);
        // The evaluation starts from the old manifold, as the serial update does in place.
        e.manifold = c->m_manifold;
        e.sensor = c->IsSensorPair();
        e.touching = c->EvaluateUpdate(e.sensor, &e.manifold);
    }
}

void b2ContactManager::EvaluateAhead(b2TaskSystem& tasks) {
    // The contacts the walk would update if no listener intervened. The walk repeats every
    // test and uses an evaluation only for a contact it updates; what an evaluation reads
    // (shapes and transforms) no step callback can change, as the world is locked.
    m_evaluatedContacts.clear();
    for (b2Contact* c = m_contactList; c; c = c->m_next) {
        if (c->m_flags & b2Contact::e_filterFlag) continue;
        if (!IsActivePair(c->GetFixtureA()->GetBody(), c->GetFixtureB()->GetBody())) continue;
        if (!FatAABBsOverlap(*c)) continue;
        m_evaluatedContacts.push_back(c);
    }
    if (m_evaluated.size() < m_evaluatedContacts.size()) m_evaluated.resize(m_evaluatedContacts.size());
    if (m_evaluatedContacts.empty()) return;
    tasks.ParallelFor(static_cast<int32>(m_evaluatedContacts.size()), kContactsPerBlock, &EvaluateRange, this);
}

bool b2ContactManager::CollideInOrder(b2Contact* c, const Evaluated* evaluated) {
    b2Fixture* fixtureA = c->GetFixtureA();
    b2Fixture* fixtureB = c->GetFixtureB();
    b2Body* bodyA = fixtureA->GetBody();
    b2Body* bodyB = fixtureB->GetBody();

    // Re-filter contacts whose filter data or body type changed.
    if (c->m_flags & b2Contact::e_filterFlag) {
        // Flagged by a listener since the evaluation: the serial path decides.
        evaluated = nullptr;
        if (!bodyB->ShouldCollide(bodyA) || !ShouldCollide(fixtureA, fixtureB)) {
            Destroy(c);
            return true;
        }
        c->m_flags &= ~b2Contact::e_filterFlag;
    }

    // At least one body must be awake and dynamic or kinematic.
    if (!IsActivePair(bodyA, bodyB)) return false;

    // Destroy contacts whose fat AABBs ceased to overlap.
    if (!FatAABBsOverlap(*c)) {
        Destroy(c);
        return true;
    }

    if (evaluated != nullptr && evaluated->sensor == c->IsSensorPair()) {
        // Counted here, on the stepping thread, exactly when the serial update would.
        AddSaturations(evaluated->saturations);
        c->UpdateFrom(m_contactListener, m_profile, evaluated->sensor, evaluated->manifold, evaluated->touching);
    } else {
        c->Update(m_contactListener, m_profile);
    }
    return true;
}

void b2ContactManager::Collide(b2TaskSystem* tasks, int32 minParallelContacts) {
    const bool parallel = tasks != nullptr && tasks->GetWorkerCount() > 1 && m_contactCount >= minParallelContacts;
    if (parallel && m_contactListener == nullptr) {
        UpdateOnWorkers(*tasks);
        return;
    }
    m_evaluatedContacts.clear();
    if (parallel) EvaluateAhead(*tasks);
    size_t nextEvaluated = 0;
    b2Contact* c = m_contactList;
    while (c) {
        // The walk meets the contacts evaluated ahead in the same order (it only removes).
        const Evaluated* evaluated = nullptr;
        if (nextEvaluated < m_evaluatedContacts.size() && m_evaluatedContacts[nextEvaluated] == c)
            evaluated = &m_evaluated[nextEvaluated++];
        b2Contact* next = c->GetNext();  // c may be destroyed
        CollideInOrder(c, evaluated);
        c = next;
    }
}

namespace {
// Contact slots per block of the workers' pass.
constexpr int32 kSlotsPerBlock = 64;
}  // namespace

bool b2ContactManager::LaterInList(const b2Contact* a, const b2Contact* b) { return a->m_listKey > b->m_listKey; }

void b2ContactManager::UpdateSlots(int32 begin, int32 end, void* self) {
    auto* manager = static_cast<b2ContactManager*>(self);
    // Counted locally and stored once: neighbouring blocks' tallies share cache lines.
    BlockTally tally;
    const SaturationCapture capture(&tally.saturations);
    for (int32 id = begin; id < end; ++id) {
        Pending& pending = manager->m_pending[static_cast<size_t>(id)];
        b2Contact* c = manager->m_contacts.Get(id);
        if (c == nullptr) {
            pending = Pending::kDone;
            continue;
        }
        // The walk's tests, on the state before the walk: what they decide here, the walk
        // would decide too, except that a body woken earlier in the list can make an inactive
        // pair active (the list-order pass sees to that).
        if (c->m_flags & b2Contact::e_filterFlag) {
            pending = Pending::kRefilter;
        } else if (!IsActivePair(c->GetFixtureA()->GetBody(), c->GetFixtureB()->GetBody())) {
            pending = Pending::kInactive;
        } else if (!manager->FatAABBsOverlap(*c)) {
            pending = Pending::kDestroy;
        } else {
            ++tally.updated;
            if (!c->IsSensorPair()) ++tally.evaluated;
            pending = c->UpdateUnobserved() ? Pending::kWake : Pending::kDone;
        }
    }
    manager->m_tallies[static_cast<size_t>(begin / kSlotsPerBlock)] = tally;
}

void b2ContactManager::UpdateOnWorkers(b2TaskSystem& tasks) {
    const int32 slots = m_contacts.GetCapacity();
    if (slots == 0) return;
    const int32 blocks = 1 + (slots - 1) / kSlotsPerBlock;
    m_pending.resize(static_cast<size_t>(slots));
    m_tallies.resize(static_cast<size_t>(blocks));
    tasks.ParallelFor(slots, kSlotsPerBlock, &UpdateSlots, this);

    uint64 saturations = 0;
    for (int32 k = 0; k < blocks; ++k) {
        const BlockTally& tally = m_tallies[static_cast<size_t>(k)];
        saturations += tally.saturations;
        if (m_profile) {
            m_profile->contactsUpdated += tally.updated;
            m_profile->manifoldsEvaluated += tally.evaluated;
        }
    }
    AddSaturations(saturations);

    m_inOrder.clear();
    m_lastWoken = WokenCounts{};
    for (int32 id = 0; id < slots; ++id) {
        const Pending pending = m_pending[static_cast<size_t>(id)];
        if (pending == Pending::kWake || pending == Pending::kDestroy || pending == Pending::kRefilter)
            m_inOrder.push_back(m_contacts.Get(id));
    }
    std::make_heap(m_inOrder.begin(), m_inOrder.end(), LaterInList);
    while (!m_inOrder.empty()) {
        std::pop_heap(m_inOrder.begin(), m_inOrder.end(), LaterInList);
        b2Contact* c = m_inOrder.back();
        m_inOrder.pop_back();
        const int64_t key = c->m_listKey;
        Pending& pending = m_pending[static_cast<size_t>(c->m_id)];
        b2Body* bodyA = c->GetFixtureA()->GetBody();
        b2Body* bodyB = c->GetFixtureB()->GetBody();
        const bool awakeA = bodyA->IsAwake();
        const bool awakeB = bodyB->IsAwake();
        if (pending == Pending::kWake) {
            pending = Pending::kDone;
            bodyA->SetAwake(true);
            bodyB->SetAwake(true);
        } else if (pending == Pending::kDestroy) {
            pending = Pending::kDone;
            Destroy(c);
        } else {
            // Refiltered, or made active by a body woken before it: the walk's own work.
            pending = CollideInOrder(c, nullptr) ? Pending::kDone : Pending::kInactive;
        }
        QueueWoken(bodyA, awakeA, key);
        QueueWoken(bodyB, awakeB, key);
    }
}

void b2ContactManager::QueueWoken(const b2Body* body, bool wasAwake, int64_t key) {
    if (wasAwake || !body->IsAwake()) return;
    for (const b2ContactEdge* edge = body->m_contactList; edge != nullptr; edge = edge->next) {
        b2Contact* c = edge->contact;
        Pending& pending = m_pending[static_cast<size_t>(c->m_id)];
        if (pending != Pending::kInactive) continue;
        if (c->m_listKey <= key) {
            ++m_lastWoken.passed;
            continue;
        }
        ++m_lastWoken.joined;
        pending = Pending::kQueued;
        m_inOrder.push_back(c);
        std::push_heap(m_inOrder.begin(), m_inOrder.end(), LaterInList);
    }
}

}  // namespace lockbox
