#pragma once
/// @file
/// b2Sweep (the manual's Math module): the motion of a body's centre of mass over a step, for
/// continuous collision. Interpolation is c0 + beta*(c - c0), one rounding per component, so
/// beta = 0 and beta = 1 give c0 and c exactly.

#include "lockbox/fixed/Transform.h"

namespace lockbox {

/// The motion of a body's centre of mass and angle over one time step, used by time of impact: the
/// centre moves linearly from c0 to c and the angle from a0 to a, starting at time fraction alpha0.
struct b2Sweep {
    b2Vec2 localCenter;  ///< centre of mass in body coordinates
    b2Vec2 c0;           ///< centre at the start of the sweep (world)
    b2Vec2 c;            ///< centre at the end of the sweep (world)
    Fixed a0;            ///< angle at the start, radians
    Fixed a;             ///< angle at the end, radians
    Fixed alpha0;        ///< fraction of the step already done, in [0, 1)

    /// The body transform at time fraction beta in [0, 1].
    void GetTransform(b2Transform* xf, Fixed beta) const noexcept {
        xf->p = c0 + beta * (c - c0);
        xf->q.Set(a0 + beta * (a - a0));
        xf->p -= b2Mul(xf->q, localCenter);
    }

    /// Moves the start of the sweep forward to time fraction alpha (alpha0 <= alpha < 1).
    constexpr void Advance(Fixed alpha) noexcept {
        const Fixed beta = (alpha - alpha0) / (Fixed(1) - alpha0);
        c0 += beta * (c - c0);
        a0 += beta * (a - a0);
        alpha0 = alpha;
    }

    /// Shifts both angles by the same whole number of turns so that a0 lies in [0, 2*pi).
    /// The shift is a multiple of the Q16.16 2*pi (raw 411775), so a - a0 is unchanged (a
    /// saturates, as any Fixed subtraction, should it leave the range).
    constexpr void Normalize() noexcept {
        constexpr int64_t kTwoPiRaw = 411775;
        // In 64 bits: near the ends of the range the whole turns below a0 pass INT32_MIN
        // (-5216 turns for a0 = -2^31 raw).
        const int64_t raw0 = a0.Raw();
        int64_t turns = raw0 / kTwoPiRaw;
        if (raw0 - turns * kTwoPiRaw < 0) --turns;  // floor
        const int64_t shift = turns * kTwoPiRaw;
        a0 = Fixed::FromRaw(static_cast<int32_t>(raw0 - shift));  // in [0, 2*pi)
        a = Fixed::FromRaw(detail::NarrowRaw(int64_t{a.Raw()} - shift, "b2Sweep::Normalize", a.Raw(), shift));
    }
};

}  // namespace lockbox
