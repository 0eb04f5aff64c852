// The island search on several workers: the islands the one-worker search finds, in its order,
// each with its bodies, contacts and joints in its order, found without a serial walk of the
// body list or of the constraint graph.
//
// The one-worker search (WorldSolve.cpp) walks the body list and, from each possible seed (an
// awake, active, non-static body) that no island took yet, walks the constraint graph depth
// first. So an island is the connected part of the graph around its seed, with static bodies
// as ends that do not join parts, and its seed is the part's first possible seed in list
// order. Here, in the stages of one parallel loop:
//  1. blocks of body slots clear the step's body flags;
//  2. blocks of contact slots clear the contacts' island marks and join the bodies of every
//     contact the search would follow, and blocks of joints join those of every joint it would
//     follow (a union-find whose links are atomic: the parts do not depend on the order);
//  3. blocks of body slots find each body's part and keep, per part, its possible seed with the
//     smallest list key; then one thread lists the seeds in list order;
//  4. blocks of seeds walk their parts from the seeds exactly as the one-worker search does.
// A part's non-static bodies, contacts and joints are reached by its walk alone, so each walk
// marks them as the one-worker search does. Static bodies are shared: a walk notes the ones it
// met in its own table instead, and leaves them as they are (the finish of the recorded islands
// wakes them, and puts them to sleep, in island order). The islands are then recorded in seed
// order, which is the one-worker order.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "dynamics/IslandWalk.h"
#include "dynamics/WorldState.h"
#include "dynamics/tasks/ScratchSet.h"
#include "dynamics/tasks/Stages.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"

namespace lockbox {

using World = core_detail::Engine::World;

namespace {
constexpr int32 kBodySlotsPerBlock = 512;
constexpr int32 kContactSlotsPerBlock = 1024;
constexpr int32 kJointsPerBlock = 1024;
// Blocks of seeds per worker: parts differ in size, and blocks taken as workers free up even
// the load out.
constexpr int32 kWalkBlocksPerWorker = 4;

// The stages of the loop.
enum Stage : int32 { e_clearBodies, e_join, e_findSeeds, e_walk };
}  // namespace

struct World::IslandSearch {
    /// One walk's buffers: the islands it found, one after the other, and its marks. It is the
    /// walk's sink (IslandWalk.h): static bodies are neither marked nor woken, only noted in
    /// its own table.
    struct Walker {
        std::vector<b2Body*> stack;
        std::vector<b2Body*> bodies;
        std::vector<b2Contact*> contacts;
        std::vector<b2Joint*> joints;
        std::vector<b2Body*> statics;
        std::vector<uint32> met;  ///< per body slot: the number of the last walk that met this static body
        uint32 walk = 0;

        void Body(b2Body* b) { bodies.push_back(b); }
        void Static(b2Body* b) { statics.push_back(b); }
        void Contact(b2Contact* c) { contacts.push_back(c); }
        void Joint(b2Joint* j) { joints.push_back(j); }
        bool Meet(b2Body& body) noexcept {
            if (body.m_type == b2_staticBody) {
                uint32& last = met[static_cast<size_t>(body.m_id)];
                if (last == walk) return false;
                last = walk;
                return true;
            }
            if (body.m_flags & b2Body::e_islandFlag) return false;
            body.m_flags |= b2Body::e_islandFlag;
            return true;
        }
    };
    /// Where one island lies in its walker's buffers.
    struct Found {
        Walker* walker = nullptr;
        int32 body = 0, bodyEnd = 0, contact = 0, contactEnd = 0, joint = 0, jointEnd = 0, statics = 0, staticsEnd = 0;
    };

    World* world = nullptr;
    b2Stages stages;
    int32 capacity = 0;  ///< body slots the per-slot arrays hold
    std::unique_ptr<std::atomic<int32>[]> parent;
    std::unique_ptr<std::atomic<b2Body*>[]> seed;  ///< per part's root: its first possible seed so far
    std::vector<b2Body*> seeds;                    ///< in list order
    std::vector<Found> found;                      ///< per seed
    b2ScratchSet<Walker> walkers;
    int32 bodyBlocks = 0, contactBlocks = 0, walkBlocks = 0;

    int32 Find(int32 id) noexcept {
        for (;;) {
            int32 up = parent[static_cast<size_t>(id)].load(std::memory_order_relaxed);
            if (up == id) return id;
            // Path halving: point at the grandparent, which is in the same part whatever
            // another worker links meanwhile (links only join roots).
            const int32 upper = parent[static_cast<size_t>(up)].load(std::memory_order_relaxed);
            if (upper != up)
                parent[static_cast<size_t>(id)].compare_exchange_weak(up, upper, std::memory_order_relaxed);
            id = upper;
        }
    }
    void Join(int32 a, int32 b) noexcept {
        for (;;) {
            a = Find(a);
            b = Find(b);
            if (a == b) return;
            // The larger root goes under the smaller, so links never make a cycle.
            if (a < b) std::swap(a, b);
            int32 expected = a;
            if (parent[static_cast<size_t>(a)].compare_exchange_strong(expected, b, std::memory_order_relaxed)) return;
        }
    }

    void ClearBodies(int32 begin, int32 end) {
        world->m_bodies.ForEachLiveIn(begin, end, [&](b2Body& b) {
            b.m_flags &= ~(b2Body::e_islandFlag | b2Body::e_fastFlag);
            parent[static_cast<size_t>(b.m_id)].store(b.m_id, std::memory_order_relaxed);
            seed[static_cast<size_t>(b.m_id)].store(nullptr, std::memory_order_relaxed);
        });
    }

    // The edges the walk follows from a non-static body to another non-static one.
    void JoinContacts(int32 begin, int32 end) {
        world->m_contactManager.ForEachInSlots(begin, end, [&](b2Contact& c) {
            c.m_flags &= ~b2Contact::e_islandFlag;
            if (!c.IsEnabled() || !c.IsTouching() || c.IsSensorPair()) return;
            const b2Body& a = *c.m_nodeB.other;
            const b2Body& b = *c.m_nodeA.other;
            if (a.m_type == b2_staticBody || b.m_type == b2_staticBody) return;
            Join(a.m_id, b.m_id);
        });
    }
    void JoinJoints(int32 begin, int32 end) {
        for (int32 k = begin; k < end; ++k) {
            const b2Joint* j = world->m_joints[static_cast<size_t>(k)];
            if (j == nullptr) continue;
            const b2Body& a = *j->m_bodyA;
            const b2Body& b = *j->m_bodyB;
            if (a.m_type == b2_staticBody || b.m_type == b2_staticBody) continue;
            if (a.m_type != b2_dynamicBody && b.m_type != b2_dynamicBody) continue;
            if (!a.IsActive() || !b.IsActive()) continue;
            Join(a.m_id, b.m_id);
        }
    }

    void FindSeeds(int32 begin, int32 end) {
        world->m_bodies.ForEachLiveIn(begin, end, [&](b2Body& b) {
            const int32 r = Find(b.m_id);
            if (b.m_type == b2_staticBody || !b.IsAwake() || !b.IsActive()) return;
            std::atomic<b2Body*>& best = seed[static_cast<size_t>(r)];
            b2Body* held = best.load(std::memory_order_relaxed);
            while (held == nullptr || b.m_listKey < held->m_listKey) {
                if (best.compare_exchange_weak(held, &b, std::memory_order_relaxed)) break;
            }
        });
    }

    // The seeds in list order (list keys are distinct).
    void ListSeeds() {
        seeds.clear();
        const int32 slots = world->m_bodies.GetCapacity();
        for (int32 id = 0; id < slots; ++id) {
            // A part's root is the one body of it that is its own parent.
            if (!world->m_bodies.IsLive(id) || parent[static_cast<size_t>(id)].load(std::memory_order_relaxed) != id)
                continue;
            b2Body* first = seed[static_cast<size_t>(id)].load(std::memory_order_relaxed);
            if (first != nullptr) seeds.push_back(first);
        }
        std::sort(seeds.begin(), seeds.end(),
                  [](const b2Body* a, const b2Body* b) { return a->m_listKey < b->m_listKey; });
        found.resize(seeds.size());
    }

    // The one-worker search's walk from `from`, into the walker's buffers.
    static void Walk(Walker& w, const JointGraph& joints, b2Body* from, Found& out) {
        if (++w.walk == 0) {
            std::fill(w.met.begin(), w.met.end(), 0u);
            w.walk = 1;
        }
        out.walker = &w;
        out.body = static_cast<int32>(w.bodies.size());
        out.contact = static_cast<int32>(w.contacts.size());
        out.joint = static_cast<int32>(w.joints.size());
        out.statics = static_cast<int32>(w.statics.size());
        WalkIsland(from, joints, w.stack, w);
        out.bodyEnd = static_cast<int32>(w.bodies.size());
        out.contactEnd = static_cast<int32>(w.contacts.size());
        out.jointEnd = static_cast<int32>(w.joints.size());
        out.staticsEnd = static_cast<int32>(w.statics.size());
        ClearScanMarks({w.bodies.data() + out.body, static_cast<size_t>(out.bodyEnd - out.body)});
    }

    void WalkSeeds(int32 block) {
        const int64_t count = static_cast<int64_t>(seeds.size());
        const auto begin = static_cast<size_t>(count * block / walkBlocks);
        const auto end = static_cast<size_t>(count * (block + 1) / walkBlocks);
        if (begin == end) return;
        const b2ScratchSet<Walker>::Lease w = walkers.Acquire();
        for (size_t i = begin; i < end; ++i) Walk(*w, world->m_jointGraph, seeds[i], found[i]);
    }

    static void RunBlock(int32 stage, int32 block, void* self) {
        IslandSearch& s = *static_cast<IslandSearch*>(self);
        switch (stage) {
            case e_clearBodies:
            case e_findSeeds: {
                const int32 slots = s.world->m_bodies.GetCapacity();
                const int32 begin = block * kBodySlotsPerBlock;
                const int32 end = std::min(begin + kBodySlotsPerBlock, slots);
                if (stage == e_clearBodies)
                    s.ClearBodies(begin, end);
                else
                    s.FindSeeds(begin, end);
                break;
            }
            case e_join:
                if (block < s.contactBlocks) {
                    const int32 begin = block * kContactSlotsPerBlock;
                    s.JoinContacts(begin,
                                   std::min(begin + kContactSlotsPerBlock, s.world->m_contactManager.SlotCount()));
                } else {
                    const int32 begin = (block - s.contactBlocks) * kJointsPerBlock;
                    s.JoinJoints(begin,
                                 std::min(begin + kJointsPerBlock, static_cast<int32>(s.world->m_joints.size())));
                }
                break;
            default: s.WalkSeeds(block); break;
        }
    }
    static int32 Next(int32 stage, void* self) {
        if (stage == e_findSeeds) static_cast<IslandSearch*>(self)->ListSeeds();
        return stage + 1;
    }
};

void World::IslandSearchDeleter::operator()(IslandSearch* p) const noexcept { delete p; }

void World::FindIslandsOnWorkers(b2TaskSystem& tasks, IslandTally& tally) {
    if (!m_islandSearch) m_islandSearch.reset(new IslandSearch);
    IslandSearch& s = *m_islandSearch;
    s.world = this;
    const int32 slots = m_bodies.GetCapacity();
    if (s.capacity < slots) {
        s.parent = std::make_unique<std::atomic<int32>[]>(static_cast<size_t>(slots));
        s.seed = std::make_unique<std::atomic<b2Body*>[]>(static_cast<size_t>(slots));
        s.capacity = slots;
    }
    const int32 workers = tasks.GetWorkerCount();
    s.walkers.Reserve(workers);
    s.walkers.ForEach([&](IslandSearch::Walker& w) {
        w.stack.reserve(static_cast<size_t>(m_bodyCount));
        w.bodies.clear();
        w.contacts.clear();
        w.joints.clear();
        w.statics.clear();
        w.met.resize(static_cast<size_t>(slots), 0);
    });

    const auto blocksOf = [](int32 items, int32 size) { return (items + size - 1) / size; };
    s.bodyBlocks = blocksOf(slots, kBodySlotsPerBlock);
    s.contactBlocks = blocksOf(m_contactManager.SlotCount(), kContactSlotsPerBlock);
    const int32 jointBlocks = blocksOf(static_cast<int32>(m_joints.size()), kJointsPerBlock);
    s.walkBlocks = kWalkBlocksPerWorker * workers;
    s.stages.Clear();
    s.stages.Add(b2Max(s.bodyBlocks, 1));
    s.stages.Add(b2Max(s.contactBlocks + jointBlocks, 1));
    s.stages.Add(b2Max(s.bodyBlocks, 1));
    s.stages.Add(s.walkBlocks);
    s.stages.Run(tasks, &IslandSearch::RunBlock, &IslandSearch::Next, &s);

    for (const IslandSearch::Found& f : s.found) {
        const IslandSearch::Walker& w = *f.walker;
        const auto part = [](const auto& list, int32 begin, int32 end) {
            return std::span(list.data() + begin, static_cast<size_t>(end - begin));
        };
        RecordIsland(part(w.bodies, f.body, f.bodyEnd), part(w.contacts, f.contact, f.contactEnd),
                     part(w.joints, f.joint, f.jointEnd), part(w.statics, f.statics, f.staticsEnd));
        tally.Add((f.bodyEnd - f.body) + (f.contactEnd - f.contact) + (f.jointEnd - f.joint));
    }
}

}  // namespace lockbox
