// b2Island: integration, the contact/joint solver loops and sleep.
#include "dynamics/Island.h"

#include "dynamics/IslandShared.h"
#include "dynamics/ProfileTimer.h"
#include "dynamics/contacts/ContactSolver.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"

namespace lockbox {

using core_detail::StageTimer;

namespace {
// One step's displacement h v, in Q32.32 for b2Body::Displace: clamps the motion (Box2D's
// maxTranslation and maxRotation) by scaling the velocity. h v is formed once, and again only
// for a clamped velocity.
void StepDisplacement(Fixed h, b2Velocity& vel, Wide& dx, Wide& dy, Wide& da) {
    dx = vel.v.x * h;
    dy = vel.v.y * h;
    const b2Vec2 translation{dx.ToFixed(), dy.ToFixed()};
    // Compare squares exactly in Q32.32 (the Q16.16 square saturates beyond 181 m).
    if (translation.LengthSquaredWide() > Wide(b2_maxTranslationSquared)) {
        const Fixed ratio = b2_maxTranslation / translation.Length();
        vel.v = ratio * vel.v;
        dx = vel.v.x * h;
        dy = vel.v.y * h;
    }
    da = vel.w * h;
    const Fixed rotation = da.ToFixed();
    if (MulWide(rotation, rotation) > Wide(b2_maxRotationSquared)) {
        const Fixed ratio = b2_maxRotation / b2Abs(rotation);
        vel.w = vel.w * ratio;
        da = vel.w * h;
    }
}
}  // namespace

b2Island::Island() = default;
b2Island::~Island() = default;

void b2Island::Reset(int32 bodyCapacity, int32 contactCapacity, int32 jointCapacity, b2ContactListener* listener,
                     int32 slotBase) {
    m_bodyCapacity = bodyCapacity;
    m_contactCapacity = contactCapacity;
    m_jointCapacity = jointCapacity;
    m_listener = listener;
    m_slotBase = slotBase;
    m_impulseSink = nullptr;
    if (m_bodies.size() < static_cast<size_t>(bodyCapacity)) m_bodies.resize(static_cast<size_t>(bodyCapacity));
    const size_t slots = static_cast<size_t>(slotBase) + static_cast<size_t>(bodyCapacity);
    if (m_positions.size() < slots) {
        m_positions.resize(slots);
        m_velocities.resize(slots);
        m_rotations.resize(slots);
    }
    if (m_contacts.size() < static_cast<size_t>(contactCapacity))
        m_contacts.resize(static_cast<size_t>(contactCapacity));
    if (m_joints.size() < static_cast<size_t>(jointCapacity)) m_joints.resize(static_cast<size_t>(jointCapacity));
    Clear();
}

b2ContactSolverDef b2Island::ContactSolverDef(const b2TimeStep& step) {
    const size_t count = static_cast<size_t>(m_contactCount);
    if (m_velocityConstraints.size() < count) {
        m_positionConstraints.resize(count);
        m_velocityConstraints.resize(count);
    }
    b2ContactSolverDef def;
    def.step = step;
    def.contacts = m_contacts.data();
    def.count = m_contactCount;
    def.positions = m_positions.data();
    def.velocities = m_velocities.data();
    def.positionConstraints = m_positionConstraints.data();
    def.velocityConstraints = m_velocityConstraints.data();
    def.rotations = m_rotations.data();
    // The lanes solve the colours of a coloured island; they read the rows' constants from the
    // lane rows, which the set-up writes.
    if (ColoursContacts() && b2ContactSolver::LanesAvailable()) {
        const size_t size = b2ContactSolver::LaneRowsSize(m_contactCount);
        if (m_laneRows.size() < size) m_laneRows.resize(size);
        def.laneRows = m_laneRows.data();
    }
    return def;
}

void b2Island::Add(b2Body* body) {
    if (m_slotBase == 0 || body->m_type != b2_staticBody) body->m_islandIndex = m_slotBase + m_bodyCount;
    m_bodies[static_cast<size_t>(m_bodyCount++)] = body;
}

void b2Island::Observe(b2IslandPhase phase) {
    if (m_observer == nullptr) return;
    const size_t n = static_cast<size_t>(m_bodyCount);
    m_observer->OnIsland(phase, std::span<b2Body* const>(m_bodies.data(), n),
                         std::span<b2Position>(m_positions.data(), n), std::span<b2Velocity>(m_velocities.data(), n));
}

void b2Island::IntegrateVelocities(int32 begin, int32 end, Fixed h, const b2Vec2& gravity) {
    for (int32 i = begin; i < end; ++i) {
        b2Body* b = m_bodies[static_cast<size_t>(i)];
        const size_t slot = static_cast<size_t>(b->m_islandIndex);
        const b2Vec2 c = b->m_sweep.c;
        const Fixed a = b->m_sweep.a;
        b2Velocity vel = b->SolverVelocity();

        // Store positions for continuous collision (a static body's never move).
        if (b->m_type != b2_staticBody) {
            b->m_sweep.c0 = b->m_sweep.c;
            b->m_sweep.a0 = b->m_sweep.a;
        }

        if (b->m_type == b2_dynamicBody) {
            // v += h * (gravityScale * g + invMass * f): the acceleration is formed in Q32.32 and
            // the velocity change is added in Q32.32, so a gentle force is not rounded away.
            const Wide ax = MulWide(b->m_gravityScale, gravity.x) + b->m_invMass * b->m_force.x;
            const Wide ay = MulWide(b->m_gravityScale, gravity.y) + b->m_invMass * b->m_force.y;
            vel.v.x += ax * h;
            vel.v.y += ay * h;
            vel.w += (b->m_invI * b->m_torque) * h;

            // Damping, the Box2D 2.3+ form v *= 1 / (1 + h c): unconditionally stable and never
            // reverses the velocity (2.2.1 clamps 1 - h c instead). One division each.
            if (b->m_linearDamping != Fixed()) {
                const Wide d = Wide(Fixed(1) + h * b->m_linearDamping);
                vel.v.x = vel.v.x / d;
                vel.v.y = vel.v.y / d;
            }
            if (b->m_angularDamping != Fixed()) vel.w = vel.w / Wide(Fixed(1) + h * b->m_angularDamping);
        }

        m_positions[slot].c = c;
        m_positions[slot].a = a;
        m_velocities[slot] = vel;
    }
}

void b2Island::IntegratePositions(int32 begin, int32 end, Fixed h) {
    for (int32 i = begin; i < end; ++i) {
        b2Body* b = m_bodies[static_cast<size_t>(i)];
        if (b->m_type == b2_staticBody) continue;  // no velocity; and islands share it
        // One island at a time, body i is in slot i: the loop stays on the solver arrays.
        const size_t slot = m_slotBase == 0 ? static_cast<size_t>(i) : static_cast<size_t>(b->m_islandIndex);
        b2Position& pos = m_positions[slot];
        b2Velocity& vel = m_velocities[slot];
        Wide dx, dy, da;
        StepDisplacement(h, vel, dx, dy, da);
        b->Displace(dx, dy, da, pos.c, pos.a);
    }
}

void b2Island::StoreBodies(int32 begin, int32 end) {
    // A static body's state is unchanged (no mass: no impulse or correction moves it), so it is
    // left alone.
    for (int32 i = begin; i < end; ++i) {
        b2Body* body = m_bodies[static_cast<size_t>(i)];
        if (body->m_type == b2_staticBody) continue;
        const size_t slot = static_cast<size_t>(body->m_islandIndex);
        body->m_sweep.c = m_positions[slot].c;
        body->m_sweep.a = m_positions[slot].a;
        body->SetSolverVelocity(m_velocities[slot]);
        body->SynchronizeTransform();
    }
}

// A contact's solve writes its dynamic bodies. Within a colour, the contacts of two points go
// after those of one, so that the lanes find quads of one point count.
b2Colours<b2Contact>::Written b2Island::WrittenBy(const b2Contact* c) {
    const b2Body* a = c->m_fixtureA->m_body;
    const b2Body* b = c->m_fixtureB->m_body;
    return {a->m_type == b2_dynamicBody ? a->m_islandIndex : -1, b->m_type == b2_dynamicBody ? b->m_islandIndex : -1,
            true, c->m_manifold.pointCount == 2};
}

// A joint solver writes both its bodies, with or without mass, so only a joint between two
// dynamic bodies may share a colour; and only the joints that touch no other body or joint (a
// gear reads two joints, a mouse joint has one body).
b2Colours<b2Joint>::Written b2Island::WrittenBy(const b2Joint* j) {
    const bool twoBodies = j->m_type == e_revoluteJoint || j->m_type == e_prismaticJoint ||
                           j->m_type == e_distanceJoint || j->m_type == e_weldJoint || j->m_type == e_wheelJoint ||
                           j->m_type == e_frictionJoint || j->m_type == e_ropeJoint;
    const bool dynamic = j->m_bodyA->m_type == b2_dynamicBody && j->m_bodyB->m_type == b2_dynamicBody;
    return {j->m_bodyA->m_islandIndex, j->m_bodyB->m_islandIndex, twoBodies && dynamic};
}

namespace {

// Fills the colouring's table of what each item writes, with workers. These reads of every
// item's bodies are most of the colouring's time, and blocks of items may do them at the same
// time; one thread reads them as the colouring goes, without the table.
template <class Item>
struct TableFill {
    Item* const* items;
    typename b2Colours<Item>::Written* table;

    static void Range(int32 begin, int32 end, void* self) {
        const TableFill& fill = *static_cast<const TableFill*>(self);
        for (int32 i = begin; i < end; ++i) fill.table[i] = b2Island::WrittenBy(fill.items[i]);
    }
};

template <class Item>
void ColourInOrder(b2Colours<Item>& colours, Item** items, int32 count, int32 slots, b2TaskSystem* tasks) {
    constexpr int32 kItemsPerBlock = 1024;
    if (tasks != nullptr && count > kItemsPerBlock) {
        TableFill<Item> fill{items, colours.Table(count)};
        tasks->ParallelFor(count, kItemsPerBlock, &TableFill<Item>::Range, &fill);
        colours.Order(items, count, slots, [table = fill.table](size_t i) { return table[i]; });
    } else {
        // The items lie scattered over the heap: ask for one some places ahead while this one
        // is read (a hint only).
        constexpr size_t kAhead = 8;
        const auto n = static_cast<size_t>(count);
        colours.Order(items, count, slots, [items, n](size_t i) {
            if (i + kAhead < n) {
                const auto* bytes = reinterpret_cast<const char*>(items[i + kAhead]);
                __builtin_prefetch(bytes);
                __builtin_prefetch(bytes + 64);
            }
            return b2Island::WrittenBy(items[i]);
        });
    }
}

}  // namespace

void b2Island::Colour() {
    const int32 slots = m_slotBase + m_bodyCount;
    if (ColoursContacts()) ColourInOrder(m_contactColours, m_contacts.data(), m_contactCount, slots, m_tasks);
    if (ColoursJoints()) ColourInOrder(m_jointColours, m_joints.data(), m_jointCount, slots, m_tasks);
}

void b2Island::SolveContactVelocities(b2ContactSolver& contacts) {
    if (!ColoursContacts()) {
        contacts.SolveVelocityConstraints();
        return;
    }
    for (int32 c = 0; c < b2_colourCount; ++c)
        contacts.SolveIndependentVelocityConstraints(m_contactColours.Start(c), m_contactColours.Start(c + 1));
    contacts.SolveVelocityConstraints(m_contactColours.Start(b2_colourCount), m_contactCount);
}

void b2Island::SolveJointVelocities(const b2SolverData& data) {
    if (!ColoursJoints()) {
        m_jointSolver.SolveVelocityConstraints(data);
        return;
    }
    for (int32 c = 0; c < b2_colourCount; ++c)
        m_jointSolver.SolveIndependentVelocityConstraints(data, m_jointColours.Start(c), m_jointColours.Start(c + 1));
    m_jointSolver.SolveVelocityConstraints(data, m_jointColours.Start(b2_colourCount), m_jointCount);
}

bool b2Island::Solve(b2Profile* profile, const b2TimeStep& step, const b2Vec2& gravity, bool allowSleep) {
    const Fixed h = step.dt;
    // A coloured island with workers runs each phase as one parallel loop of stages
    // (IslandShared.cpp); the profile then counts the velocity phase's set-up in solveVelocityNs.
    const bool shared = (ColoursContacts() || ColoursJoints()) && m_tasks != nullptr;
    // Integrate velocities and apply damping; copy the state into the solver buffers. As in
    // 2.2.1, solveInit starts after the integration (a shared solve integrates in its stages).
    if (!shared) IntegrateVelocities(0, m_bodyCount, h, gravity);
    StageTimer timer(step.timers);
    Colour();

    b2SolverData solverData;
    solverData.step = step;
    solverData.positions = m_positions.data();
    solverData.velocities = m_velocities.data();
    solverData.rotations = m_rotations.data();
    b2ContactSolverDef contactSolverDef = ContactSolverDef(step);
    b2ContactSolver contactSolver(&contactSolverDef);
    profile->bodiesIntegrated += m_bodyCount;
    profile->contactConstraints += m_contactCount;
    profile->jointConstraints += m_jointCount;
    if (shared) {
        profile->solveInitNs += timer.Nanos();
        timer.Restart();
        SolveVelocitiesShared(contactSolver, solverData, gravity);
    } else {
        contactSolver.SetUp();
        if (step.warmStarting) contactSolver.WarmStart();
        // Joint loops are entered only when the island has joints.
        if (m_jointCount > 0) m_jointSolver.InitVelocityConstraints(m_joints.data(), m_jointCount, solverData);
        profile->solveInitNs += timer.Nanos();

        timer.Restart();
        for (int32 it = 0; it < step.velocityIterations; ++it) {
            if (m_jointCount > 0) SolveJointVelocities(solverData);
            SolveContactVelocities(contactSolver);
        }
    }
    profile->velocityIterations += step.velocityIterations * m_contactCount;
    profile->jointVelocityIterations += step.velocityIterations * m_jointCount;
    if (!shared) {
        // The shared solve stored them in its last stages.
        contactSolver.StoreImpulses();
        if (m_jointCount > 0) m_jointSolver.StoreImpulses();
    }
    profile->solveVelocityNs += timer.Nanos();
    Observe(b2IslandPhase::e_velocity);

    timer.Restart();
    bool positionSolved = false;
    if (shared) {
        // Integration, the iterations and the copy back to the bodies, as stages.
        int32 iterations = 0;
        positionSolved = SolvePositionsShared(contactSolver, solverData, &iterations);
        profile->positionIterations += iterations;
        Observe(b2IslandPhase::e_position);
    } else {
        IntegratePositions(0, m_bodyCount, h);
        for (int32 it = 0; it < step.positionIterations; ++it) {
            ++profile->positionIterations;
            const bool contactsOkay = contactSolver.SolvePositionConstraints();
            const bool jointsOkay = m_jointCount == 0 || m_jointSolver.SolvePositionConstraints(solverData);
            if (contactsOkay && jointsOkay) {
                // Exit early if the position errors are small.
                positionSolved = true;
                break;
            }
        }
        Observe(b2IslandPhase::e_position);
        // Copy state buffers back to the bodies.
        StoreBodies(0, m_bodyCount);
    }
    profile->solvePositionNs += timer.Nanos();

    Report(profile, contactSolver.m_velocityConstraints);

    if (allowSleep) {
        // The sleep timer counts whole steps (NUMERICS Table 4: summing h in Q16.16 takes 31
        // steps instead of 30). Speeds are compared squared and exactly in Q32.32 (the Q16.16
        // square of linearSleepTolerance is 6.8 % off).
        int32 minSleepSteps = INT32_MAX;
        const Wide linTolSqr = MulWide(b2_linearSleepTolerance, b2_linearSleepTolerance);
        const Wide angTolSqr = MulWide(b2_angularSleepTolerance, b2_angularSleepTolerance);
        for (int32 i = 0; i < m_bodyCount; ++i) {
            b2Body* b = m_bodies[static_cast<size_t>(i)];
            if (b->GetType() == b2_staticBody) continue;
            ++profile->sleepChecks;
            if ((b->m_flags & b2Body::e_autoSleepFlag) == 0 ||
                MulWide(b->m_angularVelocity, b->m_angularVelocity) > angTolSqr ||
                b->m_linearVelocity.LengthSquaredWide() > linTolSqr) {
                b->m_sleepSteps = 0;
                minSleepSteps = 0;
            } else {
                if (b->m_sleepSteps < INT32_MAX) ++b->m_sleepSteps;
                minSleepSteps = minSleepSteps < b->m_sleepSteps ? minSleepSteps : b->m_sleepSteps;
            }
        }
        if (minSleepSteps >= step.stepsToSleep && positionSolved) {
            for (int32 i = 0; i < m_bodyCount; ++i) {
                b2Body* b = m_bodies[static_cast<size_t>(i)];
                if (b->m_type != b2_staticBody) b->SetAwake(false);
            }
            return true;
        }
    }
    return false;
}

void b2Island::SolveTOI(b2Profile* profile, const b2TimeStep& subStep, int32 toiIndexA, int32 toiIndexB) {
    for (int32 i = 0; i < m_bodyCount; ++i) {
        const b2Body* b = m_bodies[static_cast<size_t>(i)];
        m_positions[static_cast<size_t>(i)].c = b->m_sweep.c;
        m_positions[static_cast<size_t>(i)].a = b->m_sweep.a;
        m_velocities[static_cast<size_t>(i)] = b->SolverVelocity();
    }

    b2ContactSolverDef contactSolverDef = ContactSolverDef(subStep);
    b2ContactSolver contactSolver(&contactSolverDef);
    contactSolver.Load();

    // Solve position constraints.
    for (int32 i = 0; i < subStep.positionIterations; ++i) {
        ++profile->positionIterations;
        if (contactSolver.SolveTOIPositionConstraints(toiIndexA, toiIndexB)) break;
    }

    // Leap of faith to the new safe state.
    b2Body* bodyA = m_bodies[static_cast<size_t>(toiIndexA)];
    b2Body* bodyB = m_bodies[static_cast<size_t>(toiIndexB)];
    bodyA->m_sweep.c0 = m_positions[static_cast<size_t>(toiIndexA)].c;
    bodyA->m_sweep.a0 = m_positions[static_cast<size_t>(toiIndexA)].a;
    bodyB->m_sweep.c0 = m_positions[static_cast<size_t>(toiIndexB)].c;
    bodyB->m_sweep.a0 = m_positions[static_cast<size_t>(toiIndexB)].a;

    // No warm starting: the discrete solver already applied those impulses.
    contactSolver.InitializeVelocityConstraints();
    for (int32 i = 0; i < subStep.velocityIterations; ++i) contactSolver.SolveVelocityConstraints();
    // TOI impulses are not stored for warm starting: they can be very large.

    const Fixed h = subStep.dt;
    for (int32 i = 0; i < m_bodyCount; ++i) {
        b2Position& pos = m_positions[static_cast<size_t>(i)];
        b2Velocity& vel = m_velocities[static_cast<size_t>(i)];
        b2Body* body = m_bodies[static_cast<size_t>(i)];
        Wide dx, dy, da;
        StepDisplacement(h, vel, dx, dy, da);
        body->Displace(dx, dy, da, pos.c, pos.a);

        body->m_sweep.c = pos.c;
        body->m_sweep.a = pos.a;
        body->SetSolverVelocity(vel);
        body->SynchronizeTransform();
    }

    Report(profile, contactSolver.m_velocityConstraints);
}

void b2Island::Report(b2Profile* profile, const b2ContactVelocityConstraint* constraints) {
    if (m_listener == nullptr) return;
    for (int32 i = 0; i < m_contactCount; ++i) {
        b2Contact* c = m_contacts[static_cast<size_t>(i)];
        const b2ContactVelocityConstraint* vc = constraints + i;
        b2ContactImpulse impulse;
        for (int32 j = 0; j < vc->pointCount; ++j) {
            impulse.normalImpulses[j] = vc->points[j].normalImpulse;
            impulse.tangentImpulses[j] = vc->points[j].tangentImpulse;
        }
        if (m_impulseSink != nullptr) {
            m_impulseSink[i] = impulse;
            continue;
        }
        m_listener->PostSolve(c, &impulse);
        ++profile->listenerCallbacks;
    }
}

}  // namespace lockbox
