// The input widths of a contact row: the row's operations (ContactRow.h), in order, on bounds of
// bit widths (dynamics/unchecked/Widths.h) instead of values (RowSlopesBySteps, the definition),
// and the same in closed form (RowSlopes, what a step runs). Only quantities that no later sum
// contains need enter the maximum (a sum is wider than both of its terms), but a few more do,
// for clarity.
#include "dynamics/contacts/ContactRowBound.h"

namespace lockbox::solver {

Slopes RowSlopesBySteps(const RowWidths& w, int points) noexcept {
    constexpr int kWideShift = Wide::kFractionBits;
    constexpr int kFixedShift = Fixed::kFractionBits;
    const int dir = w.dir, arm = w.arm, mass = w.mass, resp = w.resp, friction = w.friction;
    const bool block = points == 2;

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
    for (int j = 0; j < points; ++j) {
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
    return widest;
}

Slopes RowSlopes(const RowWidths& w, int points) noexcept {
    // RowSlopesBySteps expanded: every step adds constants or widths and takes maxima, so each
    // slope is the largest of a few sums of widths, and grouped by what they share. A width is at
    // least 0, which is what lets a sum that another dominates drop out.
    const int speedArm = std::max(w.arm, w.dir + 2);  // the widest speed through an arm or the direction
    const int pointArm = std::max(w.arm, w.dir + 1);
    const int resp30 = std::max(w.resp, 30);
    const int friction15 = std::max(w.friction, 15);
    const int frictionTerm = std::max(w.friction, 1) + 1;
    if (points == 1) {
        return {std::max(w.mass + std::max(speedArm, 12) + resp30 - 70, pointArm + 2),
                std::max({w.mass + w.resp + resp30 + speedArm + friction15 - 115, pointArm + w.resp + friction15 - 43,
                          frictionTerm})};
    }
    return {std::max(w.mass + std::max(speedArm, 11) + resp30 - 67, pointArm + 3),
            std::max({w.mass + w.resp + resp30 + std::max(speedArm + friction15 - 112, -87),
                      pointArm + w.resp + friction15 - 42, frictionTerm})};
}

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
    RowWidths w;
    w.dir = WidthOf(Folded(vc.normal.x) | Folded(vc.normal.y) | Folded(vc.tangent.x) | Folded(vc.tangent.y));
    w.arm = WidthOf(arms);
    w.mass = WidthOf(masses);
    w.resp = WidthOf(responses);
    w.friction = WidthOf(Folded(vc.friction));
    const int bias = WidthOf(biases) + (kWideShift - kFixedShift);
    // The tangent's pushes are negated constants.
    if (w.resp > kWidestResult) return {};
    const InputWidths widths = WidthsFor(RowSlopes(w, vc.pointCount));
    if (bias > widths.velocities) return {};
    return widths;
}

}  // namespace lockbox::solver
