// The velocity iteration of one colour of joints, four revolute point rows at a time.
//
// The joints of one colour write no body in common (dynamics/Colours.h), so four point rows
// solved at once in 64-bit integer lanes give what solving them one after the other gives, as
// long as each lane computes the scalar row's very integers (dynamics/lanes/IntegerLanes.h). A
// lane that might leave the lanes' bound is not written back and is solved by the scalar row.
#include <cstdint>

#include "dynamics/joints/JointSolver.h"
#include "dynamics/lanes/IntegerLanes.h"
#include "dynamics/unchecked/UncheckedWide.h"

namespace lockbox {

using JointSolver = core_detail::Engine::Joints::Solver;

#ifdef LOCKBOX_INTEGER_LANES
namespace {
namespace jointlanes {
using namespace lanes;

// An arithmetic shift right of every lane (AVX2 has only the logical one): for a negative value
// the logical shift of its complement, complemented.
LOCKBOX_AVX2 inline Lanes ShiftRightArith(Lanes x, int n) {
    const Lanes neg = _mm256_cmpgt_epi64(Zero(), x);
    return _mm256_xor_si256(_mm256_srli_epi64(_mm256_xor_si256(x, neg), n), neg);
}

// r x P of a Q16.16 arm and a Q32.32 impulse, exact and rounded once by 2^16 with ties away from
// zero, as the scalar row's b2Cross(b2Vec2, b2WideVec2). With P = Ph 2^32 + Pl (Ph = floor(P /
// 2^32), 0 <= Pl < 2^32): e = rx Py - ry Px = H 2^32 + L, H = rx Pyh - ry Pxh and L = rx Pyl -
// ry Pxl, each exact in 64 bits for |r| < 2^30 and |P| < 2^62. Then e = M 2^16 + f with M = H 2^16
// + floor(L / 2^16) and f = L mod 2^16; e has M's sign, and the rounding adds the carry of
// f + 2^15 - [e < 0] out of 16 bits. |H| < 2^42 keeps |M| below 2^59.
LOCKBOX_AVX2 inline Lanes Cross(Lanes& unsafe, Lanes rx, Lanes ry, Lanes px, Lanes py) {
    const Split sx = SplitSign(rx), sy = SplitSign(ry);
    Flag(unsafe, _mm256_srli_epi64(_mm256_or_si256(sx.mag, sy.mag), 30));
    // Signed 32 x 32-bit products of the arms and the impulses' high words.
    const Lanes high =
        Sub(_mm256_mul_epi32(rx, _mm256_srli_epi64(py, 32)), _mm256_mul_epi32(ry, _mm256_srli_epi64(px, 32)));
    // The arms' magnitudes times the impulses' low words, then the arms' signs.
    const Lanes low =
        Sub(WithSign(_mm256_mul_epu32(sx.mag, py), sx.neg), WithSign(_mm256_mul_epu32(sy.mag, px), sy.neg));
    Flag(unsafe, _mm256_srli_epi64(SplitSign(high).mag, 42));
    const Lanes m = Add(_mm256_slli_epi64(high, 16), ShiftRightArith(low, 16));
    const Lanes f = _mm256_and_si256(low, _mm256_set1_epi64x(0xFFFF));
    const Lanes negative = _mm256_cmpgt_epi64(Zero(), m);
    const Lanes carry = _mm256_srli_epi64(Add(Add(f, _mm256_set1_epi64x(int64_t{1} << 15)), negative), 16);
    return Add(m, carry);
}

// One iteration of four point rows of one colour: JointSolver::SolvePointRow's operations in its
// order. Writes back the rows it could follow and returns a mask of the others (bit k: row k
// still to be solved).
LOCKBOX_AVX2 uint32 SolveFour(JointSolver::Row* const rows[4], b2Velocity* velocities) {
    Lanes unsafe = Zero();
    // Each lane reads its own two bodies.
    const int32 bodiesA[4] = {rows[0]->indexA, rows[1]->indexA, rows[2]->indexA, rows[3]->indexA};
    const int32 bodiesB[4] = {rows[0]->indexB, rows[1]->indexB, rows[2]->indexB, rows[3]->indexB};
    Pair p = LoadPair(unsafe, velocities, bodiesA, bodiesB);
    Lanes &vAx = p.vAx, &vAy = p.vAy, &wA = p.wA, &vBx = p.vBx, &vBy = p.vBy, &wB = p.wB;
    Lanes impulseX = LOCKBOX_LANES_OF(rows, impulse.x.Raw());
    Lanes impulseY = LOCKBOX_LANES_OF(rows, impulse.y.Raw());
    Bound(unsafe, impulseX);
    Bound(unsafe, impulseY);

    const Lanes rAx = LOCKBOX_LANES_OF(rows, rA.x.Raw()), rAy = LOCKBOX_LANES_OF(rows, rA.y.Raw());
    const Lanes rBx = LOCKBOX_LANES_OF(rows, rB.x.Raw()), rBy = LOCKBOX_LANES_OF(rows, rB.y.Raw());
    const Split sAx = SplitSign(rAx), sAy = SplitSign(rAy), sBx = SplitSign(rBx), sBy = SplitSign(rBy);

    // The velocity error at the anchors, Cdot = vB + wB x rB - vA - wA x rA.
    const Lanes cx = Sub(Sub(vBx, MulWF(unsafe, wB, sBy)), Sub(vAx, MulWF(unsafe, wA, sAy)));
    const Lanes cy = Sub(Add(vBy, MulWF(unsafe, wB, sBx)), Add(vAy, MulWF(unsafe, wA, sAx)));
    const Split scx = SplitSign(cx), scy = SplitSign(cy);
    const Split m11 = SplitSign(LOCKBOX_LANES_OF(rows, pointMass.ex.x.Raw()));
    const Split m21 = SplitSign(LOCKBOX_LANES_OF(rows, pointMass.ex.y.Raw()));
    const Split m12 = SplitSign(LOCKBOX_LANES_OF(rows, pointMass.ey.x.Raw()));
    const Split m22 = SplitSign(LOCKBOX_LANES_OF(rows, pointMass.ey.y.Raw()));
    const Lanes px = Neg(Add(MulWW(unsafe, m11, scx), MulWW(unsafe, m12, scy)));
    const Lanes py = Neg(Add(MulWW(unsafe, m21, scx), MulWW(unsafe, m22, scy)));
    impulseX = Add(impulseX, px);
    impulseY = Add(impulseY, py);

    // The increment on the bodies: A takes -mA P and -iA (rA x P), B takes mB P and iB (rB x P).
    const Split spx = SplitSign(px), spy = SplitSign(py);
    // With equal masses in every lane B's linear change is A's product, formed once (the scalar
    // row's sharing); the skipped product would have raised the very flags A's raised.
    const Lanes rawMA = LOCKBOX_LANES_OF(rows, mA.Raw()), rawMB = LOCKBOX_LANES_OF(rows, mB.Raw());
    const Split mA = SplitSign(rawMA);
    const Split iA = SplitSign(LOCKBOX_LANES_OF(rows, iA.Raw()));
    const Split iB = SplitSign(LOCKBOX_LANES_OF(rows, iB.Raw()));
    const Lanes dxA = MulWW(unsafe, mA, spx), dyA = MulWW(unsafe, mA, spy);
    vAx = Sub(vAx, dxA);
    vAy = Sub(vAy, dyA);
    wA = Sub(wA, MulWW(unsafe, Cross(unsafe, rAx, rAy, px, py), iA));
    if (AllEqual(rawMA, rawMB)) {
        vBx = Add(vBx, dxA);
        vBy = Add(vBy, dyA);
    } else {
        const Split mB = SplitSign(rawMB);
        vBx = Add(vBx, MulWW(unsafe, mB, spx));
        vBy = Add(vBy, MulWW(unsafe, mB, spy));
    }
    wB = Add(wB, MulWW(unsafe, Cross(unsafe, rBx, rBy, px, py), iB));

    // Lanes with no flag are written back; the rest are the scalar row's.
    const uint32 followed = Followed(unsafe);
    alignas(32) int64_t raw[6][4];
    SpillPair(p, raw);
    alignas(32) int64_t impulses[2][4];
    Spill(impulseX, impulses[0]);
    Spill(impulseY, impulses[1]);
    for (int k = 0; k < 4; ++k) {
        if ((followed & (1u << k)) == 0) continue;
        JointSolver::Row& row = *rows[k];
        row.impulse = b2WideVec2(Wide::FromRaw(impulses[0][k]), Wide::FromRaw(impulses[1][k]));
        b2Velocity& a = velocities[row.indexA];
        b2Velocity& b = velocities[row.indexB];
        a.v = b2WideVec2(Wide::FromRaw(raw[0][k]), Wide::FromRaw(raw[1][k]));
        a.w = Wide::FromRaw(raw[2][k]);
        b.v = b2WideVec2(Wide::FromRaw(raw[3][k]), Wide::FromRaw(raw[4][k]));
        b.w = Wide::FromRaw(raw[5][k]);
    }
    return ~followed & 0xFu;
}

}  // namespace jointlanes
}  // namespace
#endif  // LOCKBOX_INTEGER_LANES

int32 JointSolver::SolveIndependentVelocityConstraints(const b2SolverData& data, int32 begin, int32 end) {
#ifdef LOCKBOX_INTEGER_LANES
    if (lanes::Usable()) {
        // The joints write no body in common, so any order gives the same bits: each run of four
        // point rows goes to the lanes; a joint solved by itself, the rows after the last run of
        // four and the rows the lanes cannot follow go to the scalar iteration.
        const bool uncheckedAllowed = solver::UncheckedRowsAllowed();
        Row* const rows = m_rows.data();
        int32 i = begin;
        int32 inLanes = 0;
        while (i + 4 <= end) {
            Row* const quad[4] = {rows + i, rows + i + 1, rows + i + 2, rows + i + 3};
            if (quad[0]->revolute == nullptr || quad[1]->revolute == nullptr || quad[2]->revolute == nullptr ||
                quad[3]->revolute == nullptr) {
                SolveVelocityConstraints(data, i, i + 1);
                ++i;
                continue;
            }
            const uint32 rest = jointlanes::SolveFour(quad, data.velocities);
            for (int32 k = 0; k < 4; ++k) {
                if (rest & (1u << k)) {
                    SolvePointRow(*quad[k], data, uncheckedAllowed);
                } else {
                    ++inLanes;
                }
            }
            i += 4;
        }
        SolveVelocityConstraints(data, i, end);
        return inLanes;
    }
#endif
    SolveVelocityConstraints(data, begin, end);
    return 0;
}

}  // namespace lockbox
