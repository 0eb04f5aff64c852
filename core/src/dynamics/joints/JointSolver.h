#pragma once
// The joints of one island in the velocity iterations. A joint graph's iterations are bound by
// memory: each joint object is a few hundred bytes somewhere on the heap, reached through a
// pointer and a virtual call. For the common case, a revolute joint whose motor and limit are
// idle this step, the solver copies what an iteration reads (island indices, arms, inverse
// masses, the point block's inverse and the accumulated impulse) into a compact row, kept in
// one array in island order, and writes the impulse back when the iterations end. When the
// motor and the limit are both disabled, the set-up computes straight into the rows and writes
// to the joint only its state. Every other joint is solved through its own
// SolveVelocityConstraints, in the same place of the order.
// The arithmetic of a row is the joint's own, operation for operation: the bits are the same.
// While a row's inputs are within the widths its set-up derived, it runs without range tests
// (dynamics/unchecked/Widths.h), which gives the same bits again; so does its position row. In a
// colour of a coloured island, four rows at a time run in integer lanes (JointRowLanes.cpp).
//
// The rows are scratch of one island's solve, never state: snapshots and frames do not see them.

#include <span>
#include <vector>

#include "dynamics/TimeStep.h"
#include "dynamics/joints/JointAccess.h"
#include "dynamics/unchecked/UncheckedWide.h"
#include "dynamics/unchecked/Widths.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox {

class b2Joint;
class b2RevoluteJoint;

class core_detail::Engine::Joints::Solver {
public:
    /// Runs every joint's InitVelocityConstraints in island order (warm starting included) and
    /// builds the rows. The storage grows to the largest island and is then reused.
    void InitVelocityConstraints(b2Joint* const* joints, int32 count, const b2SolverData& data) {
        Begin(count);
        InitVelocityConstraints(joints, 0, count, data);
    }
    /// Sizes the rows for `count` joints; the set-up then runs over ranges of them.
    void Begin(int32 count);
    /// The set-up of joints [begin, end), in order (each writes its row and its bodies).
    void InitVelocityConstraints(b2Joint* const* joints, int32 begin, int32 end, const b2SolverData& data);
    /// One velocity iteration over the joints, in island order.
    void SolveVelocityConstraints(const b2SolverData& data) { SolveVelocityConstraints(data, 0, m_count); }
    /// The same over joints [begin, end), in order.
    void SolveVelocityConstraints(const b2SolverData& data, int32 begin, int32 end);
    /// The same over joints [begin, end) of which no two write the same body (one colour of a
    /// coloured island): the same bits, four point rows at a time where the machine has 64-bit
    /// integer lanes (JointRowLanes.cpp). Returns how many rows the lanes solved.
    int32 SolveIndependentVelocityConstraints(const b2SolverData& data, int32 begin, int32 end);
    /// Copies the rows' accumulated impulses back to their joints (for warm starting and the
    /// reaction forces). Call once after the velocity iterations.
    void StoreImpulses() const { StoreImpulses(0, m_count); }
    /// The same for joints [begin, end) (each writes its own joint).
    void StoreImpulses(int32 begin, int32 end) const;
    /// One position iteration over the joints, in island order; true when every joint is
    /// within tolerance (every joint is solved either way).
    bool SolvePositionConstraints(const b2SolverData& data) const { return SolvePositionConstraints(data, 0, m_count); }
    /// The same over joints [begin, end), in order.
    bool SolvePositionConstraints(const b2SolverData& data, int32 begin, int32 end) const;

    /// One joint in the iterations: a revolute point row, or a joint solved by itself (joint set,
    /// revolute null). 128 bytes, read front to back by an iteration.
    struct Row {
        int32 indexA = 0;  ///< island body indices
        int32 indexB = 0;
        b2Vec2 rA;  ///< arms from the centres of mass to the anchor (m)
        b2Vec2 rB;
        Wide mA, mB;                          ///< inverse masses (1/kg)
        Wide iA, iB;                          ///< inverse rotational inertias (1/(kg m^2))
        b2WideMat22 pointMass;                ///< the point block's inverse (kg)
        b2WideVec2 impulse;                   ///< accumulated point impulse (N*s)
        b2Joint* joint = nullptr;             ///< solved by itself when revolute is null
        b2RevoluteJoint* revolute = nullptr;  ///< the joint this row writes its impulse back to
        solver::InputWidths unchecked;        ///< when the row may run without range tests
    };
    /// The rows of the joints Begin sized for (tests fill them directly).
    std::span<Row> Rows() noexcept { return {m_rows.data(), static_cast<size_t>(m_count)}; }

    /// One iteration of a point row; unchecked when allowed and its inputs are within its widths.
    static void SolvePointRow(Row& row, const b2SolverData& data, bool uncheckedAllowed) noexcept;
    /// A point row's warm start: its accumulated impulse applied to its bodies, unchecked when
    /// allowed and the velocities and impulse are within its widths.
    static void WarmStartPointRow(const Row& row, const b2SolverData& data, bool uncheckedAllowed) noexcept;
    /// The widest velocities and accumulated impulse for which no value of a point row (its
    /// iterations and its warm start) can leave
    /// Q32.32 (dynamics/unchecked/Widths.h), from the widths of the row's constants.
    static solver::InputWidths PointRowWidths(const Row& row) noexcept;

    /// The widest bodies' centres and angles (poses) and correction impulses for which a
    /// position row may run without range tests (0: none).
    struct PositionWidths {
        uint8_t poses = 0;
        uint8_t impulses = 0;
    };

    /// What a position iteration of a row's joint reads (80 bytes). The anchors and centres are
    /// kept apart and subtracted in each iteration, as the joint does.
    struct PositionRow {
        int32 indexA = 0;
        int32 indexB = 0;
        b2Vec2 localAnchorA, localCenterA;
        b2Vec2 localAnchorB, localCenterB;
        Wide mA, mB, iA, iB;
        PositionWidths unchecked;  ///< when the row may run without range tests
    };

    /// The bodies' centres and angles within which a position row forms its gap and K without
    /// range tests (dynamics/unchecked/Widths.h).
    static constexpr int kPoseWidth = solver::kPoseWidth;
    /// One position iteration of a row's joint: the point-to-point part of 2.2.1's revolute
    /// SolvePositionConstraints. The gap and K are formed unchecked when allowed and the bodies
    /// are within the row's pose width, and the correction is applied unchecked when its impulse
    /// is within the row's impulse width. True when the gap is within the linear slop.
    static bool SolvePointPositionRow(const PositionRow& row, const b2SolverData& data, bool uncheckedAllowed) noexcept;
    /// The widest poses and correction impulses for which no value of a position row can leave
    /// its type, from the widths of the row's constants (zeros when its arms or K are too wide).
    static PositionWidths PositionRowWidths(const PositionRow& row) noexcept;

private:
    /// The position row of a revolute row joint: the row's bodies, masses and the anchors.
    static void LoadPositionRow(PositionRow& position, const Row& row, const b2RevoluteJoint& joint,
                                const b2Vec2& localCenterA, const b2Vec2& localCenterB) noexcept;
    /// The velocity set-up of a revolute joint with its motor and limit disabled, straight into
    /// its rows, with the arms, K and warm start unchecked where the rows' bounds prove them in
    /// range (the joint's own set-up's bits). False, with the joint and bodies untouched, when
    /// the joint needs its own set-up. Only where rows may run unchecked; elsewhere every joint
    /// takes its own set-up.
#ifdef LOCKBOX_UNCHECKED_ROWS
    static bool SetUpRow(b2RevoluteJoint& joint, const b2SolverData& data, Row& row, PositionRow& position) noexcept;
#endif

    std::vector<Row> m_rows;
    std::vector<PositionRow> m_positionRows;  ///< parallel to m_rows, set where a row is
    int32 m_count = 0;
};

}  // namespace lockbox
