// Cross-reference checks of a parsed snapshot image: after these pass, installing the image
// gives a world whose lists, edges, proxies and tree are mutually consistent, so no later
// Step can follow a dangling id, loop on a cyclic list or misread a shape.

#include <vector>

#include "SnapshotCheck.h"
#include "SnapshotImage.h"
#include "dynamics/contacts/ContactRules.h"
#include "lockbox/collision/BroadPhase.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox::state_detail {
namespace {

/// Joint ids are the smallest free ones, so the largest live id stays near the largest joint
/// count ever reached; this bound only keeps a hostile image from sizing the id table.
constexpr int32 kMaxJointId = 1 << 22;

/// Maps live pool ids to record positions; each id may be claimed once.
template <class IdOf>
void IndexByIds(std::vector<int32>& index, const PoolImage& pool, size_t records, IdOf idOf, const Image& img,
                const char* what) {
    index.assign(static_cast<size_t>(pool.capacity), -1);
    for (size_t i = 0; i < records; ++i) {
        const int32 id = idOf(img, i);
        Check(id >= 0 && id < pool.capacity && pool.live[static_cast<size_t>(id)] == 1, what,
              "id is not live in its pool", id);
        Check(index[static_cast<size_t>(id)] < 0, what, "id is listed twice", id);
        index[static_cast<size_t>(id)] = static_cast<int32>(i);
    }
}

void ValidateContacts(Image& img, const std::vector<int32>& fixtureIndex) {
    std::vector<Image::FixtureFacts>& facts = img.fixtureFacts;
    facts.resize(fixtureIndex.size());
    for (size_t id = 0; id < fixtureIndex.size(); ++id) {
        if (fixtureIndex[id] < 0) continue;  // never read: the live check below comes first
        const FixtureImage& f = img.fixtures[static_cast<size_t>(fixtureIndex[id])];
        facts[id] = {f.bodyId, f.childCount, f.shape.type};
    }
    // The registered shape orders, as a table (shape types were checked at parse).
    constexpr int32 kTypes = b2Shape::e_typeCount;
    bool registered[kTypes][kTypes];
    for (int32 a = 0; a < kTypes; ++a) {
        for (int32 b = 0; b < kTypes; ++b) {
            const auto typeA = static_cast<b2Shape::Type>(a);
            const auto typeB = static_cast<b2Shape::Type>(b);
            registered[a][b] =
                core_detail::ShapesCanCollide(typeA, typeB) && !core_detail::ShapesNeedSwap(typeA, typeB);
        }
    }
    for (const ContactImage& c : img.contacts) {
        auto fixture = [&](int32 id) -> const Image::FixtureFacts& {
            Check(id >= 0 && id < static_cast<int32>(fixtureIndex.size()) && fixtureIndex[static_cast<size_t>(id)] >= 0,
                  "contact.fixture", "is not a live fixture", id);
            return facts[static_cast<size_t>(id)];
        };
        const Image::FixtureFacts& a = fixture(c.fixtureA);
        const Image::FixtureFacts& b = fixture(c.fixtureB);
        Check(c.indexA >= 0 && c.indexA < a.childCount, "contact.childIndexA", "is out of range", c.indexA);
        Check(c.indexB >= 0 && c.indexB < b.childCount, "contact.childIndexB", "is out of range", c.indexB);
        Check(a.bodyId != b.bodyId, "contact", "joins a body to itself", a.bodyId);
        // The narrow phase casts shapes by the registered order: anything else is corrupt.
        Check(registered[a.shapeType][b.shapeType], "contact", "shape pair is not in a registered order",
              a.shapeType * 4 + b.shapeType);
    }
}

void ValidateJoints(Image& img, const std::vector<int32>& bodyIndex) {
    auto liveBody = [&](int32 id) {
        return id >= 0 && id < static_cast<int32>(bodyIndex.size()) && bodyIndex[static_cast<size_t>(id)] >= 0;
    };
    int32 maxId = -1;
    for (const JointImage& j : img.joints) {
        Check(j.id >= 0 && j.id < kMaxJointId, "joint.id", "is out of range", j.id);
        if (j.id > maxId) maxId = j.id;
        Check(liveBody(j.bodyA) && liveBody(j.bodyB), "joint.body", "is not a live body",
              liveBody(j.bodyA) ? j.bodyB : j.bodyA);
        Check(j.bodyA != j.bodyB || j.type == e_gearJoint, "joint", "joins a body to itself", j.bodyA);
    }
    std::vector<int32>& jointIndex = img.jointIndex;
    jointIndex.assign(static_cast<size_t>(maxId + 1), -1);
    for (size_t i = 0; i < img.joints.size(); ++i) {
        int32& slot = jointIndex[static_cast<size_t>(img.joints[i].id)];
        Check(slot < 0, "joint.id", "is listed twice", img.joints[i].id);
        slot = static_cast<int32>(i);
    }
    // Gear references: live revolute or prismatic joints, sides that match them.
    for (const JointImage& j : img.joints) {
        if (j.type != e_gearJoint) {
            Check(j.refCount == 0, "joint", "has references but is not a gear", j.id);
            continue;
        }
        // VisitState order: joint1, joint2, side A (body, ground), side B (body, ground).
        Check(j.refCount == 6, "gear", "reference count is not 6", j.refCount);
        const RefImage* refs = &img.refs[static_cast<size_t>(j.refBegin)];
        for (int32 s = 0; s < 2; ++s) {
            const int32 id = refs[s].id;
            Check(id >= 0 && id <= maxId && jointIndex[static_cast<size_t>(id)] >= 0, "gear.joint",
                  "is not a live joint", id);
            const JointImage& geared = img.joints[static_cast<size_t>(jointIndex[static_cast<size_t>(id)])];
            Check(geared.type == e_revoluteJoint || geared.type == e_prismaticJoint, "gear.joint",
                  "is not revolute or prismatic", id);
            const RefImage& body = refs[2 + 2 * s];
            const RefImage& ground = refs[3 + 2 * s];
            Check(body.id == geared.bodyB && ground.id == geared.bodyA, "gear.side", "bodies differ from its joint's",
                  id);
            Check((s == 0 ? j.bodyA : j.bodyB) == body.id, "gear.body", "differs from its side's body", body.id);
        }
    }
}

void ValidateTree(const Image& img, const std::vector<int32>& fixtureIndex) {
    const TreeImage& t = img.tree;
    const int32 capacity = static_cast<int32>(t.nodes.size());
    auto inRange = [&](int32 id) { return id >= 0 && id < capacity; };
    auto node = [&](int32 id) -> const b2TreeNode& { return t.nodes[static_cast<size_t>(id)]; };
    int32 allocated = 0;
    int32 leaves = 0;
    for (int32 i = 0; i < capacity; ++i) {
        const b2TreeNode& n = node(i);
        if (n.height < 0) continue;
        ++allocated;
        if (n.height == 0) {
            ++leaves;
            Check(n.child1 == b2_nullNode && n.child2 == b2_nullNode, "tree.leaf", "has children", i);
            // The leaf is exactly the proxy its key names.
            const int32 fid = b2FixtureProxy::KeyFixture(n.userData);
            const int32 child = b2FixtureProxy::KeyChild(n.userData);
            Check(fid >= 0 && fid < static_cast<int32>(fixtureIndex.size()) &&
                      fixtureIndex[static_cast<size_t>(fid)] >= 0,
                  "tree.leaf", "names no live fixture", i);
            const FixtureImage& f = img.fixtures[static_cast<size_t>(fixtureIndex[static_cast<size_t>(fid)])];
            Check(child >= 0 && child < f.proxyCount &&
                      img.proxies[static_cast<size_t>(f.proxyBegin + child)].proxyId == i,
                  "tree.leaf", "is not its fixture's proxy", i);
        } else {
            Check(inRange(n.child1) && inRange(n.child2) && n.child1 != n.child2, "tree.node", "has invalid children",
                  i);
            const b2TreeNode& c1 = node(n.child1);
            const b2TreeNode& c2 = node(n.child2);
            Check(c1.height >= 0 && c2.height >= 0 && c1.parent == i && c2.parent == i, "tree.node",
                  "children do not point back", i);
            const int32 h = 1 + (c1.height > c2.height ? c1.height : c2.height);
            Check(n.height == h, "tree.node.height", "is not 1 + the larger child height", i);
        }
        if (n.parent != b2_nullNode) {
            Check(inRange(n.parent) && node(n.parent).height > 0 &&
                      (node(n.parent).child1 == i || node(n.parent).child2 == i),
                  "tree.node.parent", "does not hold this node", i);
        } else {
            Check(i == t.root, "tree.node", "has no parent but is not the root", i);
        }
    }
    // Parent links are consistent and heights strictly decrease downwards, so every allocated
    // node hangs under the root without cycles; count them to rule out a detached subtree.
    Check(t.nodeCount == allocated, "tree.nodeCount", "differs from the allocated nodes", t.nodeCount);
    Check(t.root == b2_nullNode ? allocated == 0 : (inRange(t.root) && node(t.root).height >= 0), "tree.root",
          "is not an allocated node", t.root);
    Check(t.proxyCount == leaves && leaves == static_cast<int32>(img.proxies.size()), "broadphase.proxyCount",
          "differs from the leaves or the fixtures' proxies", t.proxyCount);
    for (const ProxyImage& p : img.proxies) {
        Check(inRange(p.proxyId) && node(p.proxyId).height == 0, "fixture.proxyId", "is not a leaf", p.proxyId);
    }
    // The free list visits every free node once.
    int32 freeCount = 0;
    for (int32 i = t.freeList; i != b2_nullNode; i = node(i).next) {
        Check(inRange(i) && node(i).height < 0 && freeCount < capacity - allocated, "tree.freeList",
              "is not a chain of the free nodes", i);
        ++freeCount;
    }
    Check(freeCount == capacity - allocated, "tree.freeList", "misses free nodes", freeCount);
    for (const int32 id : t.moveBuffer) {
        Check(id == b2BroadPhase::e_nullProxy || (inRange(id) && node(id).height == 0), "broadphase.moveBuffer",
              "holds a node that is not a leaf", id);
    }
}

}  // namespace

void ValidateImage(Image& img) {
    IndexByIds(
        img.bodyIndex, img.bodyPool, img.bodies.size(), [](const Image& m, size_t i) { return m.bodies[i].id; }, img,
        "body.id");
    IndexByIds(
        img.fixtureIndex, img.fixturePool, img.fixtures.size(),
        [](const Image& m, size_t i) { return m.fixtures[i].id; }, img, "fixture.id");
    IndexByIds(
        img.contactIndex, img.contactPool, img.contacts.size(),
        [](const Image& m, size_t i) { return m.contacts[i].id; }, img, "contact.id");
    ValidateContacts(img, img.fixtureIndex);
    ValidateJoints(img, img.bodyIndex);
    ValidateTree(img, img.fixtureIndex);
}

}  // namespace lockbox::state_detail
