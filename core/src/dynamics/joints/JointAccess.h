#pragma once
// The engine's side of the joints: the factory the world and the restores use, the links of
// the joint graph, and what a joint's solver set-up reads of its bodies.

#include "Engine.h"
#include "dynamics/TimeStep.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/joints/Joint.h"

namespace lockbox {

namespace jointmath {
/// The solver-side copy of what a joint needs from one body.
struct BodyData {
    int32 index = 0;
    b2Vec2 localCenter;
    Wide invMass;  ///< 1/kg
    Wide invI;     ///< 1/(kg*m^2)
};

/// A two-body joint's bodies as the solver holds them when its set-up starts.
struct TwoBodyState {
    BodyData A;  ///< what the joint copied of body A
    BodyData B;
    b2Vec2 cA;      ///< centre of mass of A (m)
    Fixed aA;       ///< angle of A (rad)
    b2WideVec2 vA;  ///< linear velocity of A (m/s)
    Wide wA;        ///< angular velocity of A (rad/s)
    b2Vec2 cB;
    Fixed aB;
    b2WideVec2 vB;
    Wide wB;
};
}  // namespace jointmath

struct core_detail::Engine::Joints {
    /// An island's joints in the velocity iterations, with compact rows (JointSolver.h).
    class Solver;

    /// Allocates the concrete joint for def->type (nullptr for e_unknownJoint, a definition
    /// without two distinct bodies, or a gear whose joints are not revolute or prismatic).
    static b2Joint* Create(const b2JointDef* def);
    /// An empty joint of the given type for a restore (nullptr for e_unknownJoint).
    static b2Joint* CreateEmpty(b2JointType type);
    /// Frees a joint made by Create or CreateEmpty (the world unlinks it first).
    static void Destroy(b2Joint* joint);

    /// Links one edge at the head of its body's joint list.
    static void LinkEdge(b2JointEdge* edge, b2Joint* joint, b2Body* body, b2Body* other) noexcept {
        edge->joint = joint;
        edge->other = other;
        edge->prev = nullptr;
        edge->next = body->m_jointList;
        if (body->m_jointList) body->m_jointList->prev = edge;
        body->m_jointList = edge;
    }
    /// Takes one edge out of its body's joint list.
    static void UnlinkEdge(b2JointEdge* edge, b2Body* body) noexcept {
        if (edge->prev) edge->prev->next = edge->next;
        if (edge->next) edge->next->prev = edge->prev;
        if (edge == body->m_jointList) body->m_jointList = edge->next;
        edge->prev = nullptr;
        edge->next = nullptr;
    }

    /// A body's island index, local centre and inverse masses, for a joint's solver set-up.
    static jointmath::BodyData Load(const b2Body* b) noexcept {
        return {b->m_islandIndex, b->m_sweep.localCenter, b->m_invMass, b->m_invI};
    }

    /// The set-up every two-body joint starts with: copies both bodies' island indices, local
    /// centres and inverse masses into the joint's solver fields (m_indexA, m_localCenterA,
    /// m_invMassA, m_invIA and B's) and returns their positions and velocities. Only copies:
    /// no arithmetic, so every joint's results are those of its own copy of these lines.
    template <class JointType>
    static jointmath::TwoBodyState BeginSolve(JointType& joint, const b2SolverData& data) noexcept {
        const jointmath::TwoBodyState s = LoadSolve(joint, data);
        joint.m_indexA = s.A.index;
        joint.m_indexB = s.B.index;
        joint.m_localCenterA = s.A.localCenter;
        joint.m_localCenterB = s.B.localCenter;
        joint.m_invMassA = s.A.invMass;
        joint.m_invMassB = s.B.invMass;
        joint.m_invIA = s.A.invI;
        joint.m_invIB = s.B.invI;
        return s;
    }
    /// BeginSolve without the copies into the joint: for a joint the solver's compact rows
    /// iterate, which never reads them.
    static jointmath::TwoBodyState LoadSolve(const b2Joint& joint, const b2SolverData& data) noexcept {
        const jointmath::BodyData A = Load(joint.m_bodyA), B = Load(joint.m_bodyB);
        const b2Position& pA = data.positions[A.index];
        const b2Position& pB = data.positions[B.index];
        const b2Velocity& velA = data.velocities[A.index];
        const b2Velocity& velB = data.velocities[B.index];
        return {A, B, pA.c, pA.a, velA.v, velA.w, pB.c, pB.a, velB.v, velB.w};
    }
};

}  // namespace lockbox
