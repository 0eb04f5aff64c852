// b2World::SolveTOI: continuous collision, 2.2.1's time-of-impact event loop over a short list
// of candidate contacts.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "common/KeySort.h"
#include "dynamics/WorldState.h"
#include "dynamics/contacts/ContactRules.h"
#include "lockbox/collision/TimeOfImpact.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

using World = core_detail::Engine::World;

namespace {
// A TOI at or beyond 1 - 1 raw leaves a sub-step of (1 raw) * dt, which rounds to zero time:
// treat it as no event (Box2D's 1 - 10 * FLT_EPSILON is below the Q16.16 quantum).
constexpr Fixed kTOIAlphaComplete = Fixed::FromRaw(Fixed::kOneRaw - 1);

// Position iterations of a TOI sub-step (2.2.1's literal 20).
constexpr int32 kTOIPositionIterations = 20;

// The smallest and largest of n . (xf v) over the proxy's vertices, exact but for the
// rounding of each world vertex (at most one raw per component).
void ProjectCore(const b2DistanceProxy& proxy, const b2Transform& xf, const b2Vec2& n, Wide& lo, Wide& hi) {
    lo = hi = b2DotWide(n, b2Mul(xf, proxy.m_vertices[0]));
    for (int32 i = 1; i < proxy.m_count; ++i) {
        const Wide d = b2DotWide(n, b2Mul(xf, proxy.m_vertices[i]));
        lo = d < lo ? d : lo;
        hi = d > hi ? d : hi;
    }
}

// Whether a time-of-impact query of the contact's sweeps could report an event: the cores'
// distance at the start of the sweeps, less how far any point of either body moved along them,
// comes within the query's target separation plus its tolerance (TimeOfImpact.cpp), with a
// quarter slop to spare for rounding. When it does not, the query returns "separated" and the
// contact can be skipped. `motion` is both bodies' SweptDistanceBound.
bool MayReachToiTarget(const b2Contact& c, const b2Sweep& sweepA, const b2Sweep& sweepB, Wide motion) {
    b2DistanceInput input;
    input.proxyA.Set(c.GetFixtureA()->GetShape(), c.GetChildIndexA());
    input.proxyB.Set(c.GetFixtureB()->GetShape(), c.GetChildIndexB());
    sweepA.GetTransform(&input.transformA, Fixed());
    sweepB.GetTransform(&input.transformB, Fixed());
    const Fixed totalRadius = input.proxyA.m_radius + input.proxyB.m_radius;
    const Fixed target = b2Max(b2_linearSlop, totalRadius - Fixed(3) * b2_linearSlop);
    const Wide reach = Wide(target + b2_linearSlop / 2);  // tolerance (a quarter slop) plus the spare quarter

    // The cheap test first. The cores' gap along any unit axis is at most their distance (both
    // are convex), so a gap along the manifold's normal that clears the reach by a further
    // quarter slop (far more than the roundings of this gap and of the distance below) decides
    // "no event" without the distance query. A resting contact clears it by about one slop.
    const b2Manifold* m = c.GetManifold();
    if (m->pointCount > 0 && m->type != b2Manifold::e_circles) {
        const bool faceA = m->type == b2Manifold::e_faceA;
        b2Vec2 n = b2Mul(faceA ? input.transformA.q : input.transformB.q, m->localNormal);
        if (!faceA) n = -n;  // from A to B
        Wide loA, hiA, loB, hiB;
        ProjectCore(input.proxyA, input.transformA, n, loA, hiA);
        ProjectCore(input.proxyB, input.transformB, n, loB, hiB);
        if (loB - hiA - motion >= reach + Wide(b2_linearSlop / 4)) return false;
    }

    input.useRadii = false;
    b2SimplexCache cache;
    cache.count = 0;
    b2DistanceOutput output;
    b2Distance(&output, &cache, &input);
    return Wide(output.distance) - motion < reach;
}

/// Contact slots per block of CollectToiSlots, and the fewest slots walked by slot rather than
/// down the list, and for which the built-in pool is woken (a game's task system gets any walk
/// of more than one block).
constexpr int32 kToiSlotsPerBlock = 512;
constexpr int32 kMinPoolToiSlots = 4096;
}  // namespace

// The event search of SolveTOI visits every contact of the world list in list order, and the
// contact with the smallest time of impact wins (the earlier one in the list on a tie). A
// contact can pass its filters only with a cached time of impact or a fast body (the last
// filter), so the search visits only those: the candidates, in the same order, which gives
// the same events. A contact becomes one while events are solved only when a sub-step makes
// one of its bodies fast, or when it is created; both are added as they happen. A candidate
// that a filter rejects for the rest of the step is dropped after its visit. Reading a cached
// time of impact again changes nothing, and only an event clears one (its contact's, and those
// of the dynamic bodies it moved, which become candidates again): so each candidate with a
// cached time of impact waits in a queue, earliest first, and an event's search examines only
// the candidates without one, then takes the queue's first.
bool World::RefreshToiContact(b2Contact& c, bool invalidate) noexcept {
    if (invalidate) {
        // Invalidate TOI.
        c.m_flags &= ~(b2Contact::e_toiFlag | b2Contact::e_islandFlag);
        c.m_toiCount = 0;
        c.m_toi = Fixed(1);
    }
    // The edges' other bodies are the contact's bodies, read without visiting its fixtures.
    const uint32 bodyFlags = c.m_nodeA.other->m_flags | c.m_nodeB.other->m_flags;
    return (c.m_flags & b2Contact::e_toiFlag) != 0 || (bodyFlags & b2Body::e_fastFlag) != 0;
}

void World::CollectToiSlots(int32 begin, int32 end, void* self) {
    World& world = *static_cast<World*>(self);
    std::vector<ToiKeyed>& kept = world.m_toiBlocks[static_cast<size_t>(begin / kToiSlotsPerBlock)];
    kept.clear();
    const bool invalidate = world.m_toiInvalidate;
    const bool collect = !world.m_toiSearchEveryContact;
    world.m_contactManager.ForEachInSlots(begin, end, [&](b2Contact& c) {
        if (RefreshToiContact(c, invalidate) && collect) kept.push_back(ToiKeyed{c.m_listKey, &c});
    });
}

void World::CollectToiCandidates(bool invalidate) {
    m_toiCandidates.clear();
    m_toiQueue.clear();
    const int32 slots = m_contactManager.SlotCount();
    b2TaskSystem* tasks = Tasks();
    const bool parallel = tasks != nullptr && tasks->GetWorkerCount() > 1 &&
                          slots >= (OnOwnPool() ? kMinPoolToiSlots : kToiSlotsPerBlock + 1);
    if (!parallel && slots < kMinPoolToiSlots) {
        // Few contacts (they stay in the caches): the list walk, which needs no sort.
        const bool collect = !m_toiSearchEveryContact;
        for (b2Contact* c = m_contactManager.m_contactList; c; c = c->m_next) {
            if (RefreshToiContact(*c, invalidate) && collect) AddToiCandidate(c);
        }
        m_toiSorted = m_toiCandidates.size();
        return;
    }

    // Many: by slot (memory order), in blocks that write only their own contacts and read the
    // bodies' flags, so the workers can take them.
    m_toiInvalidate = invalidate;
    const int32 blocks = (slots + kToiSlotsPerBlock - 1) / kToiSlotsPerBlock;
    if (m_toiBlocks.size() < static_cast<size_t>(blocks)) m_toiBlocks.resize(static_cast<size_t>(blocks));
    if (parallel) {
        tasks->ParallelFor(slots, kToiSlotsPerBlock, &CollectToiSlots, this);
    } else {
        for (int32 begin = 0; begin < slots; begin += kToiSlotsPerBlock)
            CollectToiSlots(begin, b2Min(begin + kToiSlotsPerBlock, slots), this);
    }
    m_toiKeyed.clear();
    for (int32 k = 0; k < blocks; ++k) {
        const std::vector<ToiKeyed>& kept = m_toiBlocks[static_cast<size_t>(k)];
        m_toiKeyed.insert(m_toiKeyed.end(), kept.begin(), kept.end());
    }
    // Slot order; the search takes them in list order, which their list keys give. Each slot
    // holds one contact and list keys are distinct, so the order has no ties.
    core_detail::SortByKey(m_toiKeyed, m_toiKeyedScratch, [](const ToiKeyed& k) { return k.listKey; });
    m_toiCandidates.reserve(m_toiKeyed.size());
    for (const ToiKeyed& k : m_toiKeyed) m_toiCandidates.push_back(k.contact);
    m_toiSorted = m_toiCandidates.size();
}

void World::AddNewToiCandidates(const b2Contact* oldHead) {
    for (b2Contact* c = m_contactManager.m_contactList; c != oldHead; c = c->m_next) AddToiCandidate(c);
}

void World::SortToiCandidates() {
    if (m_toiSorted == m_toiCandidates.size()) return;
    // List keys are distinct, so the order has no ties; a contact added twice sits next to
    // itself and is kept once.
    const auto before = [](const b2Contact* a, const b2Contact* b) { return a->m_listKey < b->m_listKey; };
    const auto middle = m_toiCandidates.begin() + static_cast<std::ptrdiff_t>(m_toiSorted);
    std::sort(middle, m_toiCandidates.end(), before);
    std::inplace_merge(m_toiCandidates.begin(), middle, m_toiCandidates.end(), before);
    m_toiCandidates.erase(std::unique(m_toiCandidates.begin(), m_toiCandidates.end()), m_toiCandidates.end());
    m_toiSorted = m_toiCandidates.size();
}

World::ToiVerdict World::ExamineToiContact(b2Contact* c) {
    if (!c->IsEnabled()) return ToiVerdict::e_kept;
    // Prevent excessive sub-stepping.
    if (c->m_toiCount > b2_maxSubSteps) return ToiVerdict::e_dropped;
    // This contact has a valid cached TOI.
    if (c->m_flags & b2Contact::e_toiFlag) return ToiVerdict::e_cached;

    b2Fixture* fA = c->GetFixtureA();
    b2Fixture* fB = c->GetFixtureB();
    if (fA->IsSensor() || fB->IsSensor()) return ToiVerdict::e_dropped;

    b2Body* bA = fA->GetBody();
    b2Body* bB = fB->GetBody();
    const b2BodyType typeA = bA->m_type;
    const b2BodyType typeB = bB->m_type;

    const bool activeA = bA->IsAwake() && typeA != b2_staticBody;
    const bool activeB = bB->IsAwake() && typeB != b2_staticBody;
    // Is at least one body active (awake and dynamic or kinematic)?
    if (!activeA && !activeB) return ToiVerdict::e_kept;

    const bool collideA = bA->IsBullet() || typeA != b2_dynamicBody;
    const bool collideB = bB->IsBullet() || typeB != b2_dynamicBody;
    // Are these two non-bullet dynamic bodies?
    if (!collideA && !collideB) return ToiVerdict::e_dropped;

    // Neither body moved enough to tunnel: the discrete step handled it.
    if (((bA->m_flags | bB->m_flags) & b2Body::e_fastFlag) == 0) return ToiVerdict::e_dropped;
    ++m_profile.toiCandidates;

    // Put the sweeps onto the same time interval.
    Fixed alpha0 = bA->m_sweep.alpha0;
    if (bA->m_sweep.alpha0 < bB->m_sweep.alpha0) {
        alpha0 = bB->m_sweep.alpha0;
        bA->m_sweep.Advance(alpha0);
    } else if (bB->m_sweep.alpha0 < bA->m_sweep.alpha0) {
        alpha0 = bA->m_sweep.alpha0;
        bB->m_sweep.Advance(alpha0);
    }

    b2TOIInput input;
    input.proxyA.Set(fA->m_shape.get(), c->GetChildIndexA());
    input.proxyB.Set(fB->m_shape.get(), c->GetChildIndexB());
    input.sweepA = bA->m_sweep;
    input.sweepB = bB->m_sweep;
    input.tMax = 1;

    b2TOIOutput output;
    b2TimeOfImpact(&output, &input);
    ++m_profile.toiCalls;

    // beta is the fraction of the remaining portion of the step.
    const Fixed beta = output.t;
    c->m_toi =
        output.state == b2TOIOutput::e_touching ? b2Min(alpha0 + (Fixed(1) - alpha0) * beta, Fixed(1)) : Fixed(1);
    c->m_flags |= b2Contact::e_toiFlag;
    return ToiVerdict::e_cached;
}

b2Contact* World::NextToiEvent() {
    // The candidates still to examine, in list order (their examination can move sweeps, so
    // the order is 2.2.1's). Those with a time of impact before the end of the step join the
    // queue; the others stay to be examined again, or are dropped.
    SortToiCandidates();
    const auto later = [](const ToiQueued& a, const ToiQueued& b) {
        return a.alpha != b.alpha ? a.alpha > b.alpha : a.listKey > b.listKey;
    };
    size_t kept = 0;
    for (b2Contact* c : m_toiCandidates) {
        const ToiVerdict verdict = ExamineToiContact(c);
        if (verdict == ToiVerdict::e_dropped) continue;
        if (verdict == ToiVerdict::e_kept) {
            m_toiCandidates[kept++] = c;
        } else if (c->m_toi < Fixed(1)) {
            m_toiQueue.push_back({c->m_toi, c->m_listKey, c});
            std::push_heap(m_toiQueue.begin(), m_toiQueue.end(), later);
        }
    }
    m_toiCandidates.resize(kept);
    m_toiSorted = kept;

    // The earliest time of impact, the earlier contact in list order on a tie: the event the
    // full search's walk would find. An entry whose contact lost its cached time of impact
    // since (an event moved a body of it) is gone; a contact disabled since goes back to the
    // candidates to examine, as the full search keeps visiting it. (The sub-step limit needs no
    // test here: only an event raises a contact's count, and it clears that contact's cache.)
    while (!m_toiQueue.empty()) {
        const ToiQueued top = m_toiQueue.front();
        std::pop_heap(m_toiQueue.begin(), m_toiQueue.end(), later);
        m_toiQueue.pop_back();
        b2Contact* c = top.contact;
        if ((c->m_flags & b2Contact::e_toiFlag) == 0 || c->m_toi != top.alpha) continue;
        if (!c->IsEnabled()) {
            AddToiCandidate(c);
            continue;
        }
        // Whatever the event does to it, it is examined again.
        AddToiCandidate(c);
        return c;
    }
    return nullptr;
}

void World::SolveTOI(const b2TimeStep& step) {
    // A body too slow to tunnel (not flagged fast) can still start the step pressed into a
    // static or kinematic body closer than the query's target (squeezed under a heavy load):
    // 2.2.1 then reports an event at the start of its sweep. Flag such a body, so that its
    // contacts are examined as 2.2.1 examines them; every other contact of slow bodies is
    // provably without an event (MayReachToiTarget).
    // The walk notes whether any body is fast, for the cheap check below.
    const bool pressedToi = (m_flags & e_skipPressedToi) == 0;
    bool anyFast = false;
    for (b2Body* b = pressedToi ? m_bodyList : nullptr; b; b = b->m_next) {
        if ((b->m_flags & b2Body::e_fastFlag) != 0) {
            anyFast = true;
            continue;
        }
        if (b->m_type == b2_staticBody) continue;
        const bool bCollidesWithAny = b->IsBullet() || b->m_type != b2_dynamicBody;
#ifndef NDEBUG
        int32 marked = 0;
        for (const b2ContactEdge* ce = b->m_contactList; ce; ce = ce->next) marked += ce->contact->m_toiBodies ? 1 : 0;
        LOCKBOX_ASSERT(marked == b->m_toiContacts, "stale count of time-of-impact body marks");
#endif
        // Only the marked contacts pass the first filter below: a body with none is done.
        if (!bCollidesWithAny && b->m_toiContacts == 0) continue;
        for (b2ContactEdge* ce = b->m_contactList; ce; ce = ce->next) {
            const b2Body* other = ce->other;
            const b2Contact* c = ce->contact;
            LOCKBOX_ASSERT(c->m_toiBodies == b2Contact::ToiBodies(*b, *other), "stale time-of-impact body mark");
            // The query loop's filters, cheapest first: one body a bullet or not dynamic (marked
            // in the contact, so the other body is read only for the pairs that pass), neither
            // examined already, one active.
            if (!bCollidesWithAny && !c->m_toiBodies) continue;
            if ((other->m_flags & b2Body::e_fastFlag) != 0) continue;
            const bool active = (b->IsAwake()) || (other->IsAwake() && other->m_type != b2_staticBody);
            if (!active) continue;
            if (!c->IsEnabled() || c->IsSensorPair()) continue;
            const Wide motion =
                b->SweptDistanceBound() + (other->m_type == b2_staticBody ? Wide() : other->SweptDistanceBound());
            const bool aFirst = c->m_nodeB.other == b;  // body A is node B's other
            const b2Sweep& sweepA = aFirst ? b->m_sweep : other->m_sweep;
            const b2Sweep& sweepB = aFirst ? other->m_sweep : b->m_sweep;
            if (MayReachToiTarget(*c, sweepA, sweepB, motion)) {
                b->m_flags |= b2Body::e_fastFlag;
                anyFast = true;
                break;
            }
        }
    }

    // The cheap check: without a fast or bullet body no contact can need a TOI event (see
    // b2Body::IsFastThisStep and the loop above), so nothing else runs.
    if (!pressedToi) {
        for (const b2Body* b = m_bodyList; b && !anyFast; b = b->m_next)
            anyFast = (b->m_flags & b2Body::e_fastFlag) != 0;
    }
    if (!anyFast) {
        m_stepComplete = true;
        return;
    }

    m_island.Reset(2 * b2_maxTOIContacts, b2_maxTOIContacts, 0, m_contactManager.m_contactListener);
    m_island.m_observer = nullptr;  // the island fenceposts cover the discrete solve only

    if (m_stepComplete) {
        m_bodies.ForEachLive([](b2Body& b) {
            b.m_flags &= ~b2Body::e_islandFlag;
            b.m_sweep.alpha0 = Fixed();
        });
    }
    CollectToiCandidates(m_stepComplete);
    uint32 filterEdits = m_toiFilterEdits;

    // Find TOI events and solve them.
    for (;;) {
        // Find the first TOI.
        b2Contact* minContact = nullptr;
        Fixed minAlpha = 1;

        if (m_toiSearchEveryContact) {
            for (b2Contact* c = m_contactManager.m_contactList; c; c = c->m_next) {
                // Ties keep the earlier contact in list order.
                if (ExamineToiContact(c) == ToiVerdict::e_cached && c->m_toi < minAlpha) {
                    minContact = c;
                    minAlpha = c->m_toi;
                }
            }
        } else {
            // A listener's edit may have made a dropped candidate acceptable again: take every
            // contact that can pass the last filter, as at the start.
            if (m_toiFilterEdits != filterEdits) {
                CollectToiCandidates(false);
                filterEdits = m_toiFilterEdits;
            }
            minContact = NextToiEvent();
            if (minContact != nullptr) minAlpha = minContact->m_toi;
        }
        if (minContact == nullptr || minAlpha >= kTOIAlphaComplete) {
            // No more TOI events. Done!
            m_stepComplete = true;
            break;
        }
        ++m_profile.toiEvents;

        // Advance the bodies to the TOI.
        b2Fixture* fA = minContact->GetFixtureA();
        b2Fixture* fB = minContact->GetFixtureB();
        b2Body* bA = fA->GetBody();
        b2Body* bB = fB->GetBody();

        const b2Sweep backup1 = bA->m_sweep;
        const b2Sweep backup2 = bB->m_sweep;
        bA->Advance(minAlpha);
        bB->Advance(minAlpha);

        // The TOI contact likely has some new contact points.
        minContact->Update(m_contactManager.m_contactListener, &m_profile);
        minContact->m_flags &= ~b2Contact::e_toiFlag;
        ++minContact->m_toiCount;

        // Is the contact solid?
        if (!minContact->IsEnabled() || !minContact->IsTouching()) {
            // Restore the sweeps.
            minContact->SetEnabled(false);
            bA->m_sweep = backup1;
            bB->m_sweep = backup2;
            bA->SynchronizeTransform();
            bB->SynchronizeTransform();
            continue;
        }

        bA->SetAwake(true);
        bB->SetAwake(true);

        // Build the island.
        m_island.Clear();
        m_island.Add(bA);
        m_island.Add(bB);
        m_island.Add(minContact);
        bA->m_flags |= b2Body::e_islandFlag;
        bB->m_flags |= b2Body::e_islandFlag;
        minContact->m_flags |= b2Contact::e_islandFlag;

        // Get contacts on bodyA and bodyB.
        b2Body* bodies[2] = {bA, bB};
        for (b2Body* body : bodies) {
            if (body->m_type != b2_dynamicBody) continue;
            for (b2ContactEdge* ce = body->m_contactList; ce; ce = ce->next) {
                if (m_island.m_bodyCount == m_island.m_bodyCapacity) break;
                if (m_island.m_contactCount == m_island.m_contactCapacity) break;

                b2Contact* contact = ce->contact;
                // Has this contact already been added to the island?
                if (contact->m_flags & b2Contact::e_islandFlag) continue;

                // Only add static, kinematic, or bullet bodies.
                b2Body* other = ce->other;
                if (other->m_type == b2_dynamicBody && !body->IsBullet() && !other->IsBullet()) continue;

                // Skip sensors.
                if (contact->IsSensorPair()) continue;

                // Tentatively advance the body to the TOI.
                const b2Sweep backup = other->m_sweep;
                if ((other->m_flags & b2Body::e_islandFlag) == 0) other->Advance(minAlpha);

                // Update the contact points.
                contact->Update(m_contactManager.m_contactListener, &m_profile);

                // Was the contact disabled by the user, or are there no contact points?
                if (!contact->IsEnabled() || !contact->IsTouching()) {
                    other->m_sweep = backup;
                    other->SynchronizeTransform();
                    continue;
                }

                // Add the contact to the island.
                contact->m_flags |= b2Contact::e_islandFlag;
                m_island.Add(contact);

                // Has the other body already been added to the island?
                if (other->m_flags & b2Body::e_islandFlag) continue;

                // Add the other body to the island.
                other->m_flags |= b2Body::e_islandFlag;
                if (other->m_type != b2_staticBody) other->SetAwake(true);
                m_island.Add(other);
            }
        }

        b2TimeStep subStep;
        subStep.dt = (Fixed(1) - minAlpha) * step.dt;
        subStep.inv_dt = subStep.dt > Fixed() ? Fixed(1) / subStep.dt : Fixed();
        subStep.dtRatio = 1;
        subStep.positionIterations = kTOIPositionIterations;
        subStep.velocityIterations = step.velocityIterations;
        subStep.stepsToSleep = step.stepsToSleep;
        subStep.warmStarting = false;
        m_island.SolveTOI(&m_profile, subStep, bA->m_islandIndex, bB->m_islandIndex);
        ++m_profile.toiSubSteps;

        // Reset island flags and synchronise broad-phase proxies.
        for (int32 i = 0; i < m_island.m_bodyCount; ++i) {
            b2Body* body = m_island.m_bodies[static_cast<size_t>(i)];
            body->m_flags &= ~b2Body::e_islandFlag;
            if (body->m_type != b2_dynamicBody) continue;
            SynchronizeFixtures(*body);
            // The sub-step moved it: it needs its TOIs re-examined.
            body->m_flags |= b2Body::e_fastFlag;
            if (IsOutside(body)) m_outOfBounds.push_back(body);

            // Invalidate all contact TOIs on this displaced body; being fast now, it makes them
            // candidates of the search.
            for (b2ContactEdge* ce = body->m_contactList; ce; ce = ce->next) {
                ce->contact->m_flags &= ~(b2Contact::e_toiFlag | b2Contact::e_islandFlag);
                AddToiCandidate(ce->contact);
            }
        }

        // Commit fixture proxy movements to the broad phase so that new contacts are created
        // (at the head of the contact list; none is destroyed here).
        const b2Contact* oldHead = m_contactManager.m_contactList;
        m_contactManager.FindNewContacts();
        AddNewToiCandidates(oldHead);

        if (m_subStepping) {
            m_stepComplete = false;
            break;
        }
    }
}

}  // namespace lockbox
