// The input limits of a contact row: the row's operations (ContactRow.h), in order, on bounds of
// bit widths instead of values.
//
// A quantity has width w when |raw| < 2^w. If the velocities have width at most Ev and the
// accumulated impulses at most Ei, each quantity of the row has width at most max(Ev + a, Ei + b)
// for slopes a and b that depend only on the row's constants, since the row multiplies inputs
// only by constants:
//   a + b, a - b      one more than the wider of a and b;
//   a * c, rounded    width(a) + width(c) - shift + 1 (the rounding adds at most one unit, and a
//   by 2^shift        product under half a unit rounds to zero, so this holds for any widths);
//   a clamp to +-m    width(m), whatever the clamped value;
//   -a                width(a).
// The velocity bias enters the row once, added to a speed; it counts as a velocity, so its width
// must not exceed Ev either. Every Wide test passes while a result has width at most 63: a product
// by a Q32.32 constant is formed in 128 bits without overflow, rounded, and fits; one by a Q16.16
// constant is formed in 64 bits, which the slopes also bound; a sum is exact and not INT64_MIN.
// So the row runs unchecked for every Ev up to 63 less the largest velocity slope, and Ei alike.
//
// The slopes below follow the row step by step; only quantities that no later sum contains need
// enter the maximum (a sum is wider than both of its terms), but a few more do, for clarity.
#include "dynamics/contacts/ContactRowBound.h"

#include <algorithm>
#include <bit>

namespace lockbox::solver {

namespace {

// The widest result every Wide operation takes without a test firing.
constexpr int kWidestResult = 63;
// The slope of a quantity that an input does not reach.
constexpr int kNone = -(1 << 20);

uint64_t Of(Wide w) noexcept { return Folded(w.Raw()); }
uint64_t Of(Fixed f) noexcept { return Folded(f.Raw()); }
// A width of every value folded into `folded` (|x| <= Folded(x) + 1 <= folded + 1).
int WidthOf(uint64_t folded) noexcept { return static_cast<int>(std::bit_width(folded + 1)); }

// A quantity's width is at most max(Ev + v, Ei + i) for velocities of width at most Ev and
// impulses of width at most Ei. Velocities and impulses are bounded apart: in a row of light
// bodies the impulses are far narrower than the speeds, and the responses that turn impulses
// into speeds far wider than one.
struct Slopes {
    int v = kNone;
    int i = kNone;
};
constexpr Slopes kVelocity{0, kNone};
constexpr Slopes kImpulse{kNone, 0};
constexpr Slopes Max(Slopes a, Slopes b) noexcept { return {std::max(a.v, b.v), std::max(a.i, b.i)}; }
// a + b or a - b.
constexpr Slopes Sum(Slopes a, Slopes b) noexcept { return {std::max(a.v, b.v) + 1, std::max(a.i, b.i) + 1}; }
// A product by a constant, which adds `grow` to the width.
constexpr Slopes Times(Slopes a, int grow) noexcept { return {a.v + grow, a.i + grow}; }

// Sets *below to the value a folded input must stay under for width at most `slope` less than
// kWidestResult; false when no width is.
bool InputLimit(int slope, uint64_t* below) noexcept {
    const int width = std::min(kWidestResult - slope, kWidestResult);
    if (width <= 0) return false;
    // Every folded input below 2^width - 1 has |raw| < 2^width.
    *below = (uint64_t{1} << width) - 1;
    return true;
}

}  // namespace

b2UncheckedLimits UncheckedLimits(const b2ContactVelocityConstraint& vc) noexcept {
    constexpr int kWideShift = Wide::kFractionBits;
    constexpr int kFixedShift = Fixed::kFractionBits;
    if (vc.pointCount != 1 && vc.pointCount != 2) return {};
    const bool block = vc.pointCount == 2;

    // The constants, by kind. A row's effective masses and its responses (pushes, turns, K) are
    // near inverses, so one width for both would make every product look far wider than it is.
    uint64_t arms = 0, masses = 0, biases = 0;
    uint64_t responses = Of(vc.pushA.x) | Of(vc.pushA.y) | Of(vc.pushB.x) | Of(vc.pushB.y);
    for (int32 j = 0; j < vc.pointCount; ++j) {
        const b2VelocityConstraintPoint& p = vc.points[j];
        arms |= Of(p.rnA) | Of(p.rnB) | Of(p.rtA) | Of(p.rtB);
        masses |= Of(p.normalMass) | Of(p.tangentMass);
        responses |= Of(p.turnNA) | Of(p.turnNB) | Of(p.turnTA) | Of(p.turnTB);
        biases |= Of(p.velocityBias);
    }
    if (block) {
        masses |= Of(vc.normalMass.k11) | Of(vc.normalMass.k12) | Of(vc.normalMass.k22);
        responses |= Of(vc.K.k11) | Of(vc.K.k12) | Of(vc.K.k22);
    }
    const int dir = WidthOf(Of(vc.normal.x) | Of(vc.normal.y) | Of(vc.tangent.x) | Of(vc.tangent.y));
    const int arm = WidthOf(arms), mass = WidthOf(masses), resp = WidthOf(responses);
    const int friction = WidthOf(Of(vc.friction));
    const int bias = WidthOf(biases) + (kWideShift - kFixedShift);
    // The tangent's pushes are negated constants.
    if (resp > kWidestResult) return {};

    // A speed (SpeedAlong) adds `speed` to the velocities' slopes: vB - vA, two products by the
    // direction and their sum, two products by the arms and two more sums; dv = vB - vA adds 1.
    const int speed = std::max(dir - kFixedShift + 5, arm - kFixedShift + 3);
    const int speedSteps = std::max(speed, 1);
    // Its products by Fixed are formed in 64 bits: |a f| + 2^15 < 2^63 needs width(a) +
    // width(f) <= 62, which adds this to the velocities' slopes (against 63).
    const int product64 = std::max(dir + 1, arm) + 1;
    const int toSpeed = mass - kWideShift + 1;  // a product by an effective mass
    const int push = resp - kWideShift + 1;     // a product by a response

    // maxFriction = normal impulse * friction (64 bits); the clamped impulse is at most
    // |maxFriction|, and its change that less the old impulse.
    const Slopes frictionChange = Sum(Times(kImpulse, friction - kFixedShift + 1), kImpulse);
    Slopes widest = Max(frictionChange, Times(kImpulse, friction + 1));
    Slopes v = kVelocity;
    for (int32 j = 0; j < vc.pointCount; ++j) {
        const Slopes lambda = Times(Times(v, speed), toSpeed);
        widest = Max(Max(widest, Times(v, speedSteps)), Max(Sum(kImpulse, lambda), Times(v, product64)));
        v = Sum(v, Times(frictionChange, push));
        widest = Max(widest, v);
    }
    const Slopes biased = Sum(Times(v, speed), kVelocity);  // vn - bias; the bias counts as a speed
    widest = Max(Max(widest, Times(v, speedSteps)), Max(biased, Times(v, product64)));
    if (!block) {
        const Slopes newImpulse = Sum(kImpulse, Times(biased, toSpeed));
        const Slopes change = Sum(newImpulse, kImpulse);
        widest = Max(Max(widest, change), Sum(v, Times(change, push)));
    } else {
        const Slopes kImpulses = Sum(Times(kImpulse, push), Times(kImpulse, push));
        const Slopes b = Sum(biased, kImpulses);
        const Slopes both = Sum(Times(b, toSpeed), Times(b, toSpeed));  // case 1, the block's inverse
        const Slopes one = Times(b, toSpeed);                           // cases 2 and 3
        const Slopes test = Sum(Times(one, push), b);                   // their K12 x + b
        const Slopes change = Sum(Max(both, one), kImpulse);            // d = x - a
        const Slopes linear = Sum(change, change);                      // d1 + d2
        const Slopes angular = Sum(Times(change, push), Times(change, push));
        widest = Max(Max(Max(widest, b), Max(both, test)), Max(Max(change, linear), angular));
        widest = Max(widest, Max(Sum(v, Times(linear, push)), Sum(v, angular)));
    }
    b2UncheckedLimits limits;
    if (!InputLimit(widest.v, &limits.velocitiesBelow) || !InputLimit(widest.i, &limits.impulsesBelow) ||
        (uint64_t{1} << bias) - 1 > limits.velocitiesBelow)
        return {};
    return limits;
}

}  // namespace lockbox::solver
