#pragma once
// Which face manifolds' position corrections (ContactPositionRow.h) may run without range tests
// (dynamics/unchecked/Widths.h): the widest poses, gap, arms and correction impulse for which no
// value of a correction can leave its format, from the widths of the constraint's local points,
// normal, radii and masses. Formed once per step, where the constraint is filled.

#include <algorithm>
#include <cstdint>

#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/unchecked/Widths.h"
#include "lockbox/common/Settings.h"

namespace lockbox::solver {

// The correction scales separation + slop by a Baumgarte factor of at most 1, which rounds to no
// more than the scaled value: the product is in range whenever its operand is.
static_assert(b2_baumgarte >= Fixed() && b2_baumgarte <= Fixed(1));
static_assert(b2_toiBaugarte >= Fixed() && b2_toiBaugarte <= Fixed(1));

inline b2ContactPositionConstraint::Widths FacePositionWidths(const b2ContactPositionConstraint& pc) noexcept {
    if (pc.type == b2Manifold::e_circles) return {};
    constexpr int kFixedWidest = 31;
    // A rotation has |c|, |s| <= 1 (raw 2^16), so |q v| <= |v.x| + |v.y|, rounding included: one
    // bit wider. The reference face's body turns the plane point and its centre, the other body
    // the clip points and its centre.
    const bool faceA = pc.type == b2Manifold::e_faceA;
    const b2Vec2& referenceCenter = faceA ? pc.localCenterA : pc.localCenterB;
    const b2Vec2& otherCenter = faceA ? pc.localCenterB : pc.localCenterA;
    const int referenceTurned = WidthOf(Folded(pc.localPoint.x) | Folded(pc.localPoint.y) | Folded(referenceCenter.x) |
                                        Folded(referenceCenter.y)) +
                                1;
    uint64_t clip = Folded(otherCenter.x) | Folded(otherCenter.y);
    for (int32 j = 0; j < b2_maxManifoldPoints && j < pc.pointCount; ++j)
        clip |= Folded(pc.localPoints[j].x) | Folded(pc.localPoints[j].y);
    // The other body's arm q p - q c (the clip point less that body's centre, exactly), and the
    // reference body's q p - q c, which the gap adds to the reference arm.
    const int otherArm = WidthOf(clip) + 1 + 1;
    const int referenceOffset = referenceTurned + 1;
    // The normal q n has |q n|^2 <= (c^2 + s^2) |n|^2 <= 2 |n|^2 (raws by 2^32), so an |n|^2 up
    // to 2^33 - 2^18 keeps each component, rounded, below 2^17.
    constexpr int kNormal = Fixed::kFractionBits + 1;
    const auto square = [](Fixed f) { return static_cast<uint64_t>(int64_t{f.Raw()} * f.Raw()); };
    if (square(pc.localNormal.x) + square(pc.localNormal.y) > (uint64_t{1} << 33) - (uint64_t{1} << 18)) return {};
    // A dot or cross with the normal: two exact products and their sum, rounded by 2^16 (x + 3
    // bits for x of width x).
    constexpr int kByNormal = kNormal + 1 - Fixed::kFractionBits + 1;
    // The separation g . n less the two radii (two sums), plus the slop (one more), must stay a
    // Fixed; the Baumgarte product then does. The gap g is the reference arm less the reference
    // body's offset: one bit wider than the wider.
    constexpr int kSeparation = kFixedWidest - 1 - 2;
    constexpr int kGap = kSeparation - kByNormal;
    if (WidthOf(Folded(pc.radiusA) | Folded(pc.radiusB)) > kSeparation) return {};

    // A K term i (r x n)^2: an exact square of r x n (arm + 3 bits) by a Wide, rounded by 2^32;
    // K sums the masses and both terms (three sums), so each term must stay within 61 bits, and
    // r x n a Fixed.
    const int mass = WidthOf(Folded(pc.invMassA) | Folded(pc.invMassB));
    const int turn = WidthOf(Folded(pc.invIA) | Folded(pc.invIB));
    if (mass + 3 > kWidestResult) return {};
    const int arm = std::min({kFixedWidest - kByNormal, (kWidestResult - 2 + 31 - turn) / 2 - kByNormal, kGap - 1});
    // Then the world points stay below 2^29 + 2^24 for poses within the pose width.
    if (otherArm > arm || referenceOffset > kGap - 1) return {};
    // An impulse of width J moves a centre by m J (rounded by 2^32: mass + J - 31 bits) times the
    // normal (rounded by 2^32: mass + J + 17 - 62 bits) and turns a body by i J (turn + J - 31
    // bits) times r x n (turn + J + arm + 3 - 62 bits). Changes within the pose width keep the
    // bodies below 2^30.
    const int impulses =
        std::min({kWidestResult, kPoseWidth + 62 - kNormal - mass, kPoseWidth + 62 - kByNormal - turn - arm});
    if (impulses <= 0) return {};
    return {static_cast<uint8_t>(kPoseWidth), static_cast<uint8_t>(arm), static_cast<uint8_t>(impulses)};
}

}  // namespace lockbox::solver
