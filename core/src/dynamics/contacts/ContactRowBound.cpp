// The input widths of a contact row: the row's operations (ContactRow.h), in order, on bounds of
// bit widths (dynamics/unchecked/Widths.h) instead of values. Only quantities that no later sum
// contains need enter the maximum (a sum is wider than both of its terms), but a few more do,
// for clarity.
#include "dynamics/contacts/ContactRowBound.h"

namespace lockbox::solver {

InputWidths UncheckedWidths(const b2ContactVelocityConstraint& vc) noexcept {
    constexpr int kWideShift = Wide::kFractionBits;
    constexpr int kFixedShift = Fixed::kFractionBits;
    if (vc.pointCount != 1 && vc.pointCount != 2) return {};
    const bool block = vc.pointCount == 2;

    // The constants, by kind. A row's effective masses and its responses (pushes, turns, K) are
    // near inverses, so one width for both would make every product look far wider than it is.
    uint64_t arms = 0, masses = 0, biases = 0;
    uint64_t responses = Folded(vc.pushA.x) | Folded(vc.pushA.y) | Folded(vc.pushB.x) | Folded(vc.pushB.y);
    for (int32 j = 0; j < vc.pointCount; ++j) {
        const b2VelocityConstraintPoint& p = vc.points[j];
        arms |= Folded(p.rnA) | Folded(p.rnB) | Folded(p.rtA) | Folded(p.rtB);
        masses |= Folded(p.normalMass) | Folded(p.tangentMass);
        responses |= Folded(p.turnNA) | Folded(p.turnNB) | Folded(p.turnTA) | Folded(p.turnTB);
        biases |= Folded(p.velocityBias);
    }
    if (block) {
        masses |= Folded(vc.normalMass.k11) | Folded(vc.normalMass.k12) | Folded(vc.normalMass.k22);
        responses |= Folded(vc.K.k11) | Folded(vc.K.k12) | Folded(vc.K.k22);
    }
    const int dir = WidthOf(Folded(vc.normal.x) | Folded(vc.normal.y) | Folded(vc.tangent.x) | Folded(vc.tangent.y));
    const int arm = WidthOf(arms), mass = WidthOf(masses), resp = WidthOf(responses);
    const int friction = WidthOf(Folded(vc.friction));
    const int bias = WidthOf(biases) + (kWideShift - kFixedShift);
    // The tangent's pushes are negated constants.
    if (resp > kWidestResult) return {};

    // A speed (SpeedAlong): vB - vA, two products by the direction and their sum, two products
    // by the arms and two more sums. `speed` is what it adds to the velocities' slopes; dv adds 1.
    const int speed = std::max(dir - kFixedShift + 5, arm - kFixedShift + 3);
    const auto speedSteps = [&](Slopes v) {
        return Max(Plus(v, std::max(speed, 1)), Product64(Plus(v, 1), std::max(dir, arm - 1)));
    };

    // maxFriction = normal impulse * friction (64 bits); the clamped impulse is at most
    // |maxFriction|, and its change that less the old one.
    const Slopes frictionChange = Sum(Times(kImpulse, friction, kFixedShift), kImpulse);
    Slopes widest = Max(frictionChange, Product64(kImpulse, friction));
    Slopes v = kVelocity;
    for (int32 j = 0; j < vc.pointCount; ++j) {
        const Slopes lambda = Times(Plus(v, speed), mass, kWideShift);
        widest = Max(Max(widest, speedSteps(v)), Sum(kImpulse, lambda));  // old + lambda
        v = Sum(v, Times(frictionChange, resp, kWideShift));
        widest = Max(widest, v);
    }
    const Slopes biased = Sum(Plus(v, speed), kVelocity);  // vn - bias; the bias counts as a speed
    widest = Max(Max(widest, speedSteps(v)), biased);
    if (!block) {
        const Slopes newImpulse = Sum(kImpulse, Times(biased, mass, kWideShift));
        const Slopes change = Sum(newImpulse, kImpulse);
        widest = Max(Max(widest, change), Sum(v, Times(change, resp, kWideShift)));
    } else {
        const Slopes kImpulses = Sum(Times(kImpulse, resp, kWideShift), Times(kImpulse, resp, kWideShift));
        const Slopes b = Sum(biased, kImpulses);
        const Slopes one = Times(b, mass, kWideShift);             // cases 2 and 3
        const Slopes both = Sum(one, one);                         // case 1, the block's inverse
        const Slopes test = Sum(Times(one, resp, kWideShift), b);  // their K12 x + b
        const Slopes change = Sum(Max(both, one), kImpulse);       // d = x - a
        const Slopes linear = Sum(change, change);                 // d1 + d2
        const Slopes angular = Sum(Times(change, resp, kWideShift), Times(change, resp, kWideShift));
        widest = Max(Max(Max(widest, b), Max(both, test)), Max(Max(change, linear), angular));
        widest = Max(widest, Max(Sum(v, Times(linear, resp, kWideShift)), Sum(v, angular)));
    }
    const InputWidths widths = WidthsFor(widest);
    if (bias > widths.velocities) return {};
    return widths;
}

}  // namespace lockbox::solver
