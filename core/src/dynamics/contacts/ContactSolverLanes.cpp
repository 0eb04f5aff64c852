// b2ContactSolver: the velocity iteration of one colour, four contacts at a time.
//
// The contacts of one colour write no body in common (dynamics/Colours.h), so solving four of
// them at once in 64-bit integer lanes gives what solving them one after the other gives, as
// long as each lane computes the scalar row's very integers. It does: every rounded product is
// formed exactly from 32 x 32-bit partial products of the magnitudes and rounded half away from
// zero, as Wide's operators round; sums are exact. Where the scalar row could saturate (and so
// report an overflow) the lanes cannot follow, so every quantity is bounded (kBoundBits): a lane
// that might leave the bound, or whose two-point contact needs a case of the block solver other
// than "both points pushing", is not written back and is solved again by the scalar row.
//
// The lane arithmetic they share with the joints' rows is dynamics/lanes/IntegerLanes.h.
#include <cstddef>

#include "SolverMath.h"
#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/lanes/IntegerLanes.h"

namespace lockbox {

namespace {
// The lane rows: each constant of a velocity row that the lanes read, stored by quads of
// constraints (4q to 4q + 3) and in a quad field by field, so that one quad's value of a field
// is one aligned load and a quad's constants are one contiguous block. Fixed values are
// widened; a velocity bias is stored as the Wide it enters the row as. (Storing the constants
// already split into magnitude and sign saved the lanes 5 % of their instructions and cost the
// set-up more than that.)
enum LaneField : int32 {
    kNormalX,
    kNormalY,
    kTangentX,
    kTangentY,
    kPushAX,
    kPushAY,
    kPushBX,
    kPushBY,
    kFriction,
    kK11,
    kK12,
    kK22,
    kMass11,
    kMass12,
    kMass22,
    kFirstPointField,
};
// Per point, from kFirstPointField + j * kPointFields.
enum LanePointField : int32 {
    kRnA,
    kRnB,
    kRtA,
    kRtB,
    kBias,
    kNormalMass,
    kTangentMass,
    kTurnNA,
    kTurnNB,
    kTurnTA,
    kTurnTB,
    kPointFields,
};
constexpr int32 kLaneFields = kFirstPointField + b2_maxManifoldPoints * kPointFields;
constexpr int32 PointField(int32 point, int32 field) noexcept {
    return kFirstPointField + point * kPointFields + field;
}
// The lane rows' first vector of the quad that holds constraint i (field f is vector f).
constexpr std::ptrdiff_t QuadOf(int32 i) noexcept {
    return static_cast<std::ptrdiff_t>(i / b2LaneQuad::kConstraints) * kLaneFields;
}

#ifdef LOCKBOX_INTEGER_LANES
// In a namespace of their own: short names, kept apart from the other solver files' helpers.
namespace contactlanes {
using namespace lanes;

// The lane rows of one quad of constraints.
struct Rows {
    const b2LaneQuad* quad;  // the quad's first field
    LOCKBOX_AVX2 Lanes Load(int32 field) const {
        return _mm256_load_si256(reinterpret_cast<const Lanes*>(quad + field));
    }
    LOCKBOX_AVX2 Split LoadSplit(int32 field) const { return SplitSign(Load(field)); }
};

// solver::SpeedAlong in lanes: d . (vB - vA) + wB armB - wA armA.
LOCKBOX_AVX2 inline Lanes SpeedAlong(Lanes& unsafe, const Pair& p, const Split& dx, const Split& dy, const Split& armA,
                                     const Split& armB) {
    const Lanes linear = Add(MulWF(unsafe, Sub(p.vBx, p.vAx), dx), MulWF(unsafe, Sub(p.vBy, p.vAy), dy));
    return Sub(Add(linear, MulWF(unsafe, p.wB, armB)), MulWF(unsafe, p.wA, armA));
}

// The linear responses of the two bodies to an impulse along a direction (split once, used
// by every iteration's rows).
struct Push {
    Split ax, ay, bx, by;
    bool same = false;  ///< pushB is pushA in every lane (equal masses)
};

// An impulse d along a push: A's linear velocities lose d pushA, B's gain d pushB. With equal
// pushes in every lane B's change is A's product, formed once (the scalar row's PushPair); the
// skipped product would have raised the very flags A's raised.
LOCKBOX_AVX2 inline void PushLinear(Lanes& unsafe, Pair& p, const Split& d, const Push& push) {
    const Lanes dxA = MulWW(unsafe, d, push.ax), dyA = MulWW(unsafe, d, push.ay);
    p.vAx = Sub(p.vAx, dxA);
    p.vAy = Sub(p.vAy, dyA);
    p.vBx = Add(p.vBx, push.same ? dxA : MulWW(unsafe, d, push.bx));
    p.vBy = Add(p.vBy, push.same ? dyA : MulWW(unsafe, d, push.by));
}

// solver::ApplyAlong in lanes.
LOCKBOX_AVX2 inline void ApplyAlong(Lanes& unsafe, Pair& p, Lanes lambda, const Push& push, const Split& turnA,
                                    const Split& turnB) {
    const Split l = SplitSign(lambda);
    PushLinear(unsafe, p, l, push);
    p.wA = Sub(p.wA, MulWW(unsafe, l, turnA));
    p.wB = Add(p.wB, MulWW(unsafe, l, turnB));
}

// One velocity iteration of four contacts of one colour with `points` points each, the scalar
// row's operations in its order. Writes back the lanes it could follow and returns a mask of
// the others (bit k: constraint k still to be solved).
LOCKBOX_AVX2 uint32 SolveFour(b2ContactVelocityConstraint* const vc[4], const Rows& rows, b2Velocity* velocities,
                              int32 points) {
    Lanes unsafe = Zero();
    // Each lane reads its own two bodies.
    const int32 bodiesA[4] = {vc[0]->indexA, vc[1]->indexA, vc[2]->indexA, vc[3]->indexA};
    const int32 bodiesB[4] = {vc[0]->indexB, vc[1]->indexB, vc[2]->indexB, vc[3]->indexB};
    Pair p = LoadPair(unsafe, velocities, bodiesA, bodiesB);

    const Split nx = rows.LoadSplit(kNormalX), ny = rows.LoadSplit(kNormalY);
    const Split tx = rows.LoadSplit(kTangentX), ty = rows.LoadSplit(kTangentY);
    const Lanes pushAX = rows.Load(kPushAX), pushAY = rows.Load(kPushAY);
    const Lanes pushBX = rows.Load(kPushBX), pushBY = rows.Load(kPushBY);
    const bool samePush = AllEqual(pushAX, pushBX) && AllEqual(pushAY, pushBY);
    const Push normalPush{SplitSign(pushAX), SplitSign(pushAY), SplitSign(pushBX), SplitSign(pushBY), samePush};
    // The tangent (n.y, -n.x) pushes by (push.y, -push.x).
    const Push tangentPush{normalPush.ay, Flip(normalPush.ax), normalPush.by, Flip(normalPush.bx), samePush};
    const Split friction = rows.LoadSplit(kFriction);

    Lanes normalImpulse[b2_maxManifoldPoints], tangentImpulse[b2_maxManifoldPoints];
    for (int32 j = 0; j < points; ++j) {
        normalImpulse[j] = LOCKBOX_LANES_OF(vc, points[j].normalImpulse.Raw());
        tangentImpulse[j] = LOCKBOX_LANES_OF(vc, points[j].tangentImpulse.Raw());
        Bound(unsafe, normalImpulse[j]);
        Bound(unsafe, tangentImpulse[j]);
    }

    // Friction first, as the scalar row.
    for (int32 j = 0; j < points; ++j) {
        const Split rtA = rows.LoadSplit(PointField(j, kRtA));
        const Split rtB = rows.LoadSplit(PointField(j, kRtB));
        const Lanes vt = SpeedAlong(unsafe, p, tx, ty, rtA, rtB);
        Lanes lambda = Neg(MulWW(unsafe, vt, rows.LoadSplit(PointField(j, kTangentMass))));
        const Lanes maxFriction = MulWF(unsafe, normalImpulse[j], friction);
        const Lanes newImpulse = Max(Neg(maxFriction), Min(Add(tangentImpulse[j], lambda), maxFriction));
        lambda = Sub(newImpulse, tangentImpulse[j]);
        tangentImpulse[j] = newImpulse;
        ApplyAlong(unsafe, p, lambda, tangentPush, rows.LoadSplit(PointField(j, kTurnTA)),
                   rows.LoadSplit(PointField(j, kTurnTB)));
    }

    if (points == 1) {
        const Split rnA = rows.LoadSplit(PointField(0, kRnA));
        const Split rnB = rows.LoadSplit(PointField(0, kRnB));
        const Lanes bias = rows.Load(PointField(0, kBias));
        const Lanes vn = SpeedAlong(unsafe, p, nx, ny, rnA, rnB);
        Lanes lambda = Neg(MulWW(unsafe, Sub(vn, bias), rows.LoadSplit(PointField(0, kNormalMass))));
        const Lanes newImpulse = Max(Add(normalImpulse[0], lambda), Zero());
        lambda = Sub(newImpulse, normalImpulse[0]);
        normalImpulse[0] = newImpulse;
        ApplyAlong(unsafe, p, lambda, normalPush, rows.LoadSplit(PointField(0, kTurnNA)),
                   rows.LoadSplit(PointField(0, kTurnNB)));
    } else {
        // The block solver's first case (both points pushing), which resting contacts take; a
        // lane that needs another case is left to the scalar row.
        const Lanes a1 = normalImpulse[0], a2 = normalImpulse[1];
        const Split sa1 = SplitSign(a1), sa2 = SplitSign(a2);
        const Lanes vn1 =
            SpeedAlong(unsafe, p, nx, ny, rows.LoadSplit(PointField(0, kRnA)), rows.LoadSplit(PointField(0, kRnB)));
        const Lanes vn2 =
            SpeedAlong(unsafe, p, nx, ny, rows.LoadSplit(PointField(1, kRnA)), rows.LoadSplit(PointField(1, kRnB)));
        const Split k11 = rows.LoadSplit(kK11), k12 = rows.LoadSplit(kK12), k22 = rows.LoadSplit(kK22);
        const Lanes bias1 = rows.Load(PointField(0, kBias));
        const Lanes bias2 = rows.Load(PointField(1, kBias));
        const Lanes b1 = Sub(Sub(vn1, bias1), Add(MulWW(unsafe, k11, sa1), MulWW(unsafe, k12, sa2)));
        const Lanes b2 = Sub(Sub(vn2, bias2), Add(MulWW(unsafe, k12, sa1), MulWW(unsafe, k22, sa2)));
        const Split m11 = rows.LoadSplit(kMass11), m12 = rows.LoadSplit(kMass12), m22 = rows.LoadSplit(kMass22);
        const Split sb1 = SplitSign(b1), sb2 = SplitSign(b2);
        const Lanes x1 = Neg(Add(MulWW(unsafe, m11, sb1), MulWW(unsafe, m12, sb2)));
        const Lanes x2 = Neg(Add(MulWW(unsafe, m12, sb1), MulWW(unsafe, m22, sb2)));
        Flag(unsafe, _mm256_or_si256(_mm256_cmpgt_epi64(Zero(), x1), _mm256_cmpgt_epi64(Zero(), x2)));
        const Split d1 = SplitSign(Sub(x1, a1)), d2 = SplitSign(Sub(x2, a2));
        // Both impulses act along the normal: one linear impulse, two lever arms.
        const Split d = SplitSign(Add(Sub(x1, a1), Sub(x2, a2)));
        PushLinear(unsafe, p, d, normalPush);
        p.wA = Sub(p.wA, Add(MulWW(unsafe, d1, rows.LoadSplit(PointField(0, kTurnNA))),
                             MulWW(unsafe, d2, rows.LoadSplit(PointField(1, kTurnNA)))));
        p.wB = Add(p.wB, Add(MulWW(unsafe, d1, rows.LoadSplit(PointField(0, kTurnNB))),
                             MulWW(unsafe, d2, rows.LoadSplit(PointField(1, kTurnNB)))));
        normalImpulse[0] = x1;
        normalImpulse[1] = x2;
    }

    // Lanes with no flag are written back; the rest are the scalar row's.
    const uint32 followed = Followed(unsafe);
    alignas(32) int64_t raw[6][4];
    SpillPair(p, raw);
    alignas(32) int64_t normal[b2_maxManifoldPoints][4], tangent[b2_maxManifoldPoints][4];
    for (int32 j = 0; j < points; ++j) {
        Spill(normalImpulse[j], normal[j]);
        Spill(tangentImpulse[j], tangent[j]);
    }
    for (int k = 0; k < 4; ++k) {
        if ((followed & (1u << k)) == 0) continue;
        b2ContactVelocityConstraint* c = vc[k];
        for (int32 j = 0; j < points; ++j) {
            c->points[j].normalImpulse = Wide::FromRaw(normal[j][k]);
            c->points[j].tangentImpulse = Wide::FromRaw(tangent[j][k]);
        }
        const b2WideVec2 vA(Wide::FromRaw(raw[0][k]), Wide::FromRaw(raw[1][k]));
        const b2WideVec2 vB(Wide::FromRaw(raw[3][k]), Wide::FromRaw(raw[4][k]));
        solver::Store(velocities[c->indexA], vA, Wide::FromRaw(raw[2][k]), c->invMassA, c->invIA);
        solver::Store(velocities[c->indexB], vB, Wide::FromRaw(raw[5][k]), c->invMassB, c->invIB);
    }
    return ~followed & 0xFu;
}

}  // namespace contactlanes
#endif  // LOCKBOX_INTEGER_LANES

}  // namespace

size_t b2ContactSolver::LaneRowsSize(int32 count) noexcept {
    return static_cast<size_t>(kLaneFields) *
           static_cast<size_t>(b2LaneQuad::CeilBoundary(count) / b2LaneQuad::kConstraints);
}

void b2ContactSolver::StoreLaneRows(int32 begin, int32 end) {
    for (int32 i = begin; i < end; ++i) {
        b2LaneQuad* const quad = m_laneRows + QuadOf(i);
        const int32 lane = i - b2LaneQuad::FloorBoundary(i);
        auto at = [quad, lane](int32 field, int64_t raw) { quad[field].lane[lane] = raw; };
        const b2ContactVelocityConstraint& vc = m_velocityConstraints[i];
        at(kNormalX, vc.normal.x.Raw());
        at(kNormalY, vc.normal.y.Raw());
        at(kTangentX, vc.tangent.x.Raw());
        at(kTangentY, vc.tangent.y.Raw());
        at(kPushAX, vc.pushA.x.Raw());
        at(kPushAY, vc.pushA.y.Raw());
        at(kPushBX, vc.pushB.x.Raw());
        at(kPushBY, vc.pushB.y.Raw());
        at(kFriction, vc.friction.Raw());
        // The block matrices are read only for two-point rows, which set them.
        at(kK11, vc.K.k11.Raw());
        at(kK12, vc.K.k12.Raw());
        at(kK22, vc.K.k22.Raw());
        at(kMass11, vc.normalMass.k11.Raw());
        at(kMass12, vc.normalMass.k12.Raw());
        at(kMass22, vc.normalMass.k22.Raw());
        for (int32 j = 0; j < vc.pointCount; ++j) {
            const b2VelocityConstraintPoint& p = vc.points[j];
            at(PointField(j, kRnA), p.rnA.Raw());
            at(PointField(j, kRnB), p.rnB.Raw());
            at(PointField(j, kRtA), p.rtA.Raw());
            at(PointField(j, kRtB), p.rtB.Raw());
            at(PointField(j, kBias), Wide(p.velocityBias).Raw());
            at(PointField(j, kNormalMass), p.normalMass.Raw());
            at(PointField(j, kTangentMass), p.tangentMass.Raw());
            at(PointField(j, kTurnNA), p.turnNA.Raw());
            at(PointField(j, kTurnNB), p.turnNB.Raw());
            at(PointField(j, kTurnTA), p.turnTA.Raw());
            at(PointField(j, kTurnTB), p.turnTB.Raw());
        }
    }
}

bool b2ContactSolver::LanesAvailable() noexcept {
#ifdef LOCKBOX_INTEGER_LANES
    return lanes::HasAvx2();
#else
    return false;
#endif
}

void b2ContactSolver::AllowLanes(bool allow) noexcept { lanes::Allow(allow); }

int32 b2ContactSolver::SolveIndependentVelocityConstraints(int32 begin, int32 end) {
#ifdef LOCKBOX_INTEGER_LANES
    if (m_laneRows != nullptr && lanes::Usable()) {
        // The constraints write no body in common, so any order gives the same bits: each quad
        // of the lane rows whose constraints have one point count goes to the lanes; the
        // constraints before the first quad, in mixed quads and after the last go to the
        // scalar row, and so do the lanes' rows the lanes cannot follow.
        int32 i = b2Min(end, b2LaneQuad::CeilBoundary(begin));
        int32 inLanes = 0;
        SolveVelocityConstraints(begin, i);
        for (; i + 4 <= end; i += 4) {
            b2ContactVelocityConstraint* const first = m_velocityConstraints + i;
            b2ContactVelocityConstraint* const vc[4] = {first, first + 1, first + 2, first + 3};
            const int32 points = vc[0]->pointCount;
            if (vc[1]->pointCount != points || vc[2]->pointCount != points || vc[3]->pointCount != points) {
                SolveVelocityConstraints(i, i + 4);
                continue;
            }
            const uint32 rest =
                contactlanes::SolveFour(vc, contactlanes::Rows{m_laneRows + QuadOf(i)}, m_velocities, points);
            for (int32 k = 0; k < 4; ++k) {
                if (rest & (1u << k)) {
                    SolveVelocityConstraints(i + k, i + k + 1);
                } else {
                    ++inLanes;
                }
            }
        }
        SolveVelocityConstraints(i, end);
        return inLanes;
    }
#endif
    SolveVelocityConstraints(begin, end);
    return 0;
}

}  // namespace lockbox
