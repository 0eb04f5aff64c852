#pragma once
// b2Island (Box2D 2.2.1 b2Island.h): a connected group of awake bodies, contacts and joints,
// solved together; also the small island of a time-of-impact event.

#include <memory>
#include <vector>

#include "Engine.h"
#include "dynamics/Colours.h"
#include "dynamics/TimeStep.h"
#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/joints/JointSolver.h"
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/Profile.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/fixed/Math.h"

namespace lockbox {

class b2Body;
class b2Contact;
class b2Joint;
class b2ContactListener;
class b2StepObserver;
class b2TaskSystem;
enum class b2IslandPhase : uint32;

/// An island: buffers reused between islands and steps (capacity grows, never shrinks).
class core_detail::Engine::Island {
public:
    Island();
    ~Island();
    Island(const Island&) = delete;
    Island& operator=(const Island&) = delete;

    /// Sets the capacities, the listener and the slot base (m_slotBase) for the next islands.
    void Reset(int32 bodyCapacity, int32 contactCapacity, int32 jointCapacity, b2ContactListener* listener,
               int32 slotBase = 0);
    /// Empties the island (keeps the buffers).
    void Clear() noexcept {
        m_bodyCount = 0;
        m_contactCount = 0;
        m_jointCount = 0;
    }

    /// Discrete solve: integrate velocities (gravity, forces, damping), warm start, velocity
    /// iterations, integrate positions, position iterations, then the sleep test.
    /// Returns whether the island fell asleep. Static bodies are shared between islands, so
    /// the solve never writes them: the caller sets an island's static bodies asleep with it.
    bool Solve(b2Profile* profile, const b2TimeStep& step, const b2Vec2& gravity, bool allowSleep);
    /// Time-of-impact sub-step: position solve that moves only the two TOI bodies, then a
    /// velocity solve and integration of the remaining time.
    void SolveTOI(b2Profile* profile, const b2TimeStep& subStep, int32 toiIndexA, int32 toiIndexB);

    void Add(b2Body* body);
    void Add(b2Contact* contact) { m_contacts[static_cast<size_t>(m_contactCount++)] = contact; }
    void Add(b2Joint* joint) { m_joints[static_cast<size_t>(m_jointCount++)] = joint; }

    /// Reports one phase of the discrete solve to m_observer, if any.
    void Observe(b2IslandPhase phase);

    /// Calls PostSolve for every contact with the impulses of its constraint, or, with
    /// m_impulseSink set, writes those impulses there instead.
    void Report(b2Profile* profile, const b2ContactVelocityConstraint* constraints);

    /// Whether the island's contacts, and its joints, are many enough to be solved in colour
    /// order (Colours.h).
    bool ColoursContacts() const noexcept { return b2Coloured(m_contactCount); }
    bool ColoursJoints() const noexcept { return b2Coloured(m_jointCount); }
    /// Puts the contacts and the joints that are many enough in colour order.
    void Colour();
    /// The solver slots a contact's solve writes (Colours.h).
    static b2Colours<b2Contact>::Written WrittenBy(const b2Contact* c);
    /// The same for a joint's, and whether it may share a colour at all.
    static b2Colours<b2Joint>::Written WrittenBy(const b2Joint* j);

    /// One velocity iteration over the contacts: in island order, or colour by colour (each
    /// colour's contacts write no body in common), then the overflow in order.
    void SolveContactVelocities(b2ContactSolver& contacts);
    /// The same over the joints (their colours' joints write no body in common either).
    void SolveJointVelocities(const b2SolverData& data);

    /// Bodies [begin, end): integrate velocities (gravity, forces, damping) and copy the state
    /// into the solver buffers.
    void IntegrateVelocities(int32 begin, int32 end, Fixed h, const b2Vec2& gravity);
    /// Bodies [begin, end): move by the solved velocities (clamped to Box2D's maximum motion).
    void IntegratePositions(int32 begin, int32 end, Fixed h);
    /// Bodies [begin, end): copy the solver buffers back and synchronise the transforms.
    void StoreBodies(int32 begin, int32 end);

    /// A coloured island's velocity phase (integration, contact and joint set-up, warm start,
    /// iterations) as stages on m_tasks: the bits of the one-thread loops in colour order.
    void SolveVelocitiesShared(b2ContactSolver& contacts, const b2SolverData& data, const b2Vec2& gravity);
    /// Its position phase likewise (integration, iterations, copy back to the bodies); returns
    /// whether the last iteration was accepted and sets how many ran.
    bool SolvePositionsShared(b2ContactSolver& contacts, const b2SolverData& data, int32* iterationsRun);

    /// A contact-solver definition over this island, its constraint storage grown to fit.
    b2ContactSolverDef ContactSolverDef(const b2TimeStep& step);

    b2ContactListener* m_listener = nullptr;
    /// Solver slot of the island's first own body. 0 for one island at a time; for islands
    /// solved at the same time it is the world's static body count, and every static body keeps
    /// one world-wide slot below it (set by the world before the solves), so that no solve writes
    /// a static body's m_islandIndex.
    int32 m_slotBase = 0;
    /// When set, Solve records each contact's impulses here (in island contact order) instead
    /// of calling PostSolve, which the world then calls in island order.
    b2ContactImpulse* m_impulseSink = nullptr;
    b2StepObserver* m_observer = nullptr;  ///< island fenceposts of the discrete solve (not state)
    std::vector<b2Body*> m_bodies;
    std::vector<b2Contact*> m_contacts;
    std::vector<b2Joint*> m_joints;
    std::vector<b2Position> m_positions;
    std::vector<b2Velocity> m_velocities;
    // Contact-solver storage, sized to the largest island so far (grown, never shrunk).
    std::vector<b2ContactPositionConstraint> m_positionConstraints;
    std::vector<b2ContactVelocityConstraint> m_velocityConstraints;
    std::vector<b2CachedRot> m_rotations;   ///< per body, like m_positions
    std::vector<b2LaneQuad> m_laneRows;     ///< the lanes' constants of a coloured island (grown, never shrunk)
    b2Colours<b2Contact> m_contactColours;  ///< the colour order of a large island's contacts
    b2Colours<b2Joint> m_jointColours;      ///< and of its joints, when they are many
    /// Workers for a coloured island's loops (IslandShared.h), or nullptr: one thread. Set by
    /// the world only where the island is solved on the thread stepping it.
    b2TaskSystem* m_tasks = nullptr;
    struct Shared;
    std::unique_ptr<Shared> m_shared;                   ///< the stages of a shared solve, made on first use
    core_detail::Engine::Joints::Solver m_jointSolver;  ///< the joints' rows, sized to the largest island so far
    int32 m_bodyCount = 0;
    int32 m_jointCount = 0;
    int32 m_contactCount = 0;
    int32 m_bodyCapacity = 0;
    int32 m_contactCapacity = 0;
    int32 m_jointCapacity = 0;
};

using b2Island = core_detail::Engine::Island;

}  // namespace lockbox
