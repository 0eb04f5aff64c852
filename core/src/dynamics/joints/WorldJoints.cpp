// b2World::CreateJoint and DestroyJoint (Box2D 2.2.1 b2World.cpp), with lockbox's gear rule:
// a gear joint never outlives the joints it couples.
#include "dynamics/WorldState.h"
#include "dynamics/joints/JointAccess.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/GearJoint.h"

namespace lockbox {

using World = core_detail::Engine::World;

namespace {
using Joints = core_detail::Engine::Joints;

// Contacts between the two bodies must be re-filtered when a joint changes whether they may
// collide.
void FlagContactsBetween(b2Body* body, const b2Body* other) {
    for (b2ContactEdge* edge = body->GetContactList(); edge; edge = edge->next) {
        if (edge->other == other) edge->contact->FlagForFiltering();
    }
}
}  // namespace

b2Joint* World::CreateJoint(const b2JointDef* def) {
    if (CheckLocked("b2World::CreateJoint called inside a Step callback (the world is locked)")) return nullptr;
    b2Joint* j = Joints::Create(def);
    if (j == nullptr) return nullptr;

    // The smallest free id: ids are small, stable and independent of addresses. Every id
    // below m_jointIdHint is taken, so the scan starts there.
    size_t id = static_cast<size_t>(m_jointIdHint);
    while (id < m_joints.size() && m_joints[id] != nullptr) ++id;
    if (id == m_joints.size()) m_joints.push_back(nullptr);
    m_joints[id] = j;
    j->m_id = static_cast<int32>(id);
    m_jointIdHint = static_cast<int32>(id) + 1;
    MarkJointStructureChanged(*j);

    // Connect to the world list, newest first.
    j->m_prev = nullptr;
    j->m_next = m_jointList;
    if (m_jointList) m_jointList->m_prev = j;
    m_jointList = j;
    ++m_jointCount;

    // Connect to the bodies' doubly linked lists.
    Joints::LinkEdge(&j->m_edgeA, j, j->m_bodyA, j->m_bodyB);
    Joints::LinkEdge(&j->m_edgeB, j, j->m_bodyB, j->m_bodyA);

    // If the joint prevents collisions, flag any contacts for filtering.
    if (!def->collideConnected) FlagContactsBetween(j->m_bodyB, j->m_bodyA);

    // Note: creating a joint doesn't wake the bodies (as 2.2.1).
    return j;
}

void World::DestroyJoint(b2Joint* j) {
    if (CheckLocked("b2World::DestroyJoint called inside a Step callback (the world is locked)")) return;
    if (j == nullptr) return;
    MarkJointStructureChanged(*j);

    // Gears coupling this joint go first (each is told to the destruction listener: it is an
    // implicit destruction). A gear is never coupled by another gear, so this recursion is
    // one level deep.
    if (j->GetType() == e_revoluteJoint || j->GetType() == e_prismaticJoint) {
        b2Joint* k = m_jointList;
        while (k) {
            b2Joint* next = k->m_next;
            if (k->GetType() == e_gearJoint) {
                auto* gear = static_cast<b2GearJoint*>(k);
                if (gear->GetJoint1() == j || gear->GetJoint2() == j) {
                    if (m_destructionListener) m_destructionListener->SayGoodbye(k);
                    // The gear may be next in the list: restart the scan after removing it.
                    DestroyJoint(k);
                    next = m_jointList;
                }
            }
            k = next;
        }
    }

    const bool collideConnected = j->m_collideConnected;

    // Remove from the world list.
    if (j->m_prev) j->m_prev->m_next = j->m_next;
    if (j->m_next) j->m_next->m_prev = j->m_prev;
    if (j == m_jointList) m_jointList = j->m_next;

    b2Body* bodyA = j->m_bodyA;
    b2Body* bodyB = j->m_bodyB;

    // Wake up the connected bodies.
    bodyA->SetAwake(true);
    bodyB->SetAwake(true);

    Joints::UnlinkEdge(&j->m_edgeA, bodyA);
    Joints::UnlinkEdge(&j->m_edgeB, bodyB);

    ReleaseJointId(j->m_id);
    Joints::Destroy(j);
    --m_jointCount;

    // If the joint prevented collisions, flag any contacts for filtering.
    if (!collideConnected) FlagContactsBetween(bodyB, bodyA);
}

void World::ReleaseJointId(int32 id) {
    m_joints[static_cast<size_t>(id)] = nullptr;
    // Trailing free ids are dropped so the table's size follows the largest live id.
    while (!m_joints.empty() && m_joints.back() == nullptr) m_joints.pop_back();
    if (id < m_jointIdHint) m_jointIdHint = id;
}

}  // namespace lockbox
