#pragma once
// The engine's own code, gathered under one name so that the core's public classes (b2World,
// b2Body, b2Fixture, b2Contact, b2Joint and the joints, b2WorldFrame) need only one friend:
// each of them declares `friend struct core_detail::Engine;` and keeps its data private.
//
// C++ gives a nested class the access of its enclosing class, so every part of the engine
// that reads or writes those internals is a nested class of Engine, declared here and defined
// in its own header or source file. Code that only needs a world's internal state (its pools,
// lists, switches and frame book-keeping) reaches it through Engine::Of, whose members are
// public to the engine. Nothing here is installed: public headers only forward-declare Engine.

#include "lockbox/common/Settings.h"

namespace lockbox {

class b2World;

namespace core_detail {

struct Engine {
    // ---- the step (dynamics/) ----
    /// A world's state and the code of its public calls (dynamics/WorldState.h).
    class World;
    /// Slot storage with stable addresses and LIFO id reuse (dynamics/Pool.h).
    template <typename T, int32 kBlockSize = 64>
    class Pool;
    /// Broad-phase pairs to contacts, narrow phase (dynamics/ContactManager.h).
    class ContactManager;
    /// One island's integration and solver loops (dynamics/Island.h).
    class Island;
    /// The contact constraints of one island (dynamics/contacts/ContactSolver.h).
    class ContactSolver;
    /// The few body and contact internals other code reads (dynamics/Access.h).
    struct Bodies;
    struct Contacts;
    /// The joint factory, the joint graph's links, and what joints read of bodies
    /// (dynamics/joints/JointAccess.h).
    struct Joints;
    /// Each body's joint edges in one array, for the island search (dynamics/JointGraph.h).
    class JointGraph;

    // ---- the world's state (state/) ----
    /// The canonical state walk's body, fixture, contact and joint records (state/StateWalk.h).
    struct StateWalk;
    /// The joints' state fields on prototypes, for the parse and the record sizes
    /// (state/JointState.h).
    struct JointState;
    /// The list links the restores write (state/RestoreLinks.h).
    struct RestoreLinks;
    /// Installing a validated snapshot image (state/SnapshotApply.cpp).
    struct SnapshotApply;
    /// Rollback frames: their arrays and the undoing of creations (state/WorldFrame.cpp).
    struct Frames;

    /// The internal state of a world.
    static World& Of(b2World& world) noexcept;
    static const World& Of(const b2World& world) noexcept;
};

}  // namespace core_detail
}  // namespace lockbox
