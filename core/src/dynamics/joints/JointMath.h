#pragma once
// Internal helpers shared by the joint solvers: applying Q32.32 impulses to the Q32.32 solver
// velocities and to Q16.16 positions, and the soft-constraint coefficients.

#include "dynamics/TimeStep.h"
#include "dynamics/joints/JointAccess.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/fixed/Math.h"
#include "lockbox/fixed/WideMatrix.h"

namespace lockbox::jointmath {

// What a joint's solver set-up reads of one body (JointAccess.h).
inline BodyData Load(const b2Body* b) noexcept { return core_detail::Engine::Joints::Load(b); }

// The shared set-up of a two-body joint's InitVelocityConstraints (JointAccess.h).
template <class JointType>
inline TwoBodyState BeginSolve(JointType& joint, const b2SolverData& data) noexcept {
    return core_detail::Engine::Joints::BeginSolve(joint, data);
}

// v -= invMass * P, w -= invI * (r x P), added to the Q32.32 velocities (no Q16.16 rounding).
inline void ApplyNeg(b2WideVec2& v, Wide& w, const BodyData& b, const b2Vec2& r, const b2WideVec2& p) noexcept {
    v.x -= b.invMass * p.x;
    v.y -= b.invMass * p.y;
    w -= b.invI * b2Cross(r, p);
}

// v += invMass * P, w += invI * (r x P).
inline void ApplyPos(b2WideVec2& v, Wide& w, const BodyData& b, const b2Vec2& r, const b2WideVec2& p) noexcept {
    v.x += b.invMass * p.x;
    v.y += b.invMass * p.y;
    w += b.invI * b2Cross(r, p);
}

// The same two for a position correction (Q16.16 centre and angle), each component rounded once.
inline void ApplyNeg(b2Vec2& c, Fixed& a, const BodyData& b, const b2Vec2& r, const b2WideVec2& p) noexcept {
    c.x -= MulToFixed(b.invMass, p.x);
    c.y -= MulToFixed(b.invMass, p.y);
    a -= MulToFixed(b.invI, b2Cross(r, p));
}
inline void ApplyPos(b2Vec2& c, Fixed& a, const BodyData& b, const b2Vec2& r, const b2WideVec2& p) noexcept {
    c.x += MulToFixed(b.invMass, p.x);
    c.y += MulToFixed(b.invMass, p.y);
    a += MulToFixed(b.invI, b2Cross(r, p));
}

// x += a b and x -= a b: exact to 2^-32 on a Q32.32 velocity, rounded once on a Q16.16
// position; so one joint function can apply an impulse to either.
inline void AddProduct(Wide& x, Wide a, Wide b) noexcept { x += a * b; }
inline void AddProduct(Fixed& x, Wide a, Wide b) noexcept { x += MulToFixed(a, b); }
inline void SubProduct(Wide& x, Wide a, Wide b) noexcept { x -= a * b; }
inline void SubProduct(Fixed& x, Wide a, Wide b) noexcept { x -= MulToFixed(a, b); }

// A line impulse P with angular parts LA and LB (prismatic and wheel joints): A takes
// -mA P and -iA LA, B takes mB P and iB LB; on velocities or positions (AddProduct).
template <class Vec, class Scalar>
inline void ApplyLineImpulse(Vec& vA, Scalar& wA, Vec& vB, Scalar& wB, Wide mA, Wide mB, Wide iA, Wide iB,
                             const b2WideVec2& P, Wide LA, Wide LB) noexcept {
    SubProduct(vA.x, mA, P.x);
    SubProduct(vA.y, mA, P.y);
    SubProduct(wA, iA, LA);
    AddProduct(vB.x, mB, P.x);
    AddProduct(vB.y, mB, P.y);
    AddProduct(wB, iB, LB);
}

// Angular-only update: w += invI * L.
inline void ApplyAngular(Wide& w, Wide invI, Wide l) noexcept { w += invI * l; }

// Velocity of the point at arm r: v + w x r (m/s), in Q32.32.
inline b2WideVec2 PointVelocity(const b2WideVec2& v, Wide w, const b2Vec2& r) noexcept {
    return {v.x - w * r.y, v.y + w * r.x};
}

// Relative velocity of B's anchor point to A's, rounded once to Q16.16: the Cdot that a joint's
// Q16.16 constraint algebra works on.
inline b2Vec2 RelativeVelocity(const b2WideVec2& vA, Wide wA, const b2Vec2& rA, const b2WideVec2& vB, Wide wB,
                               const b2Vec2& rB) noexcept {
    return (PointVelocity(vB, wB, rB) - PointVelocity(vA, wA, rA)).ToFixed();
}

// d . v for a Q16.16 direction and a Q32.32 velocity (m/s), one rounding per product.
inline Wide DotW(const b2Vec2& d, const b2WideVec2& v) noexcept { return v.x * d.x + v.y * d.y; }

// Exact r x d of two Q16.16 vectors, kept in Q32.32 (arm times direction, m).
inline Wide CrossW(const b2Vec2& r, const b2Vec2& d) noexcept { return b2CrossWide(r, d); }

// invMass + invI * a^2 for an arm term a (m): the scalar effective inverse mass of one body.
inline Wide InvMassTerm(Wide invMass, Wide invI, Wide armSq) noexcept { return invMass + invI * armSq; }

// The point-to-point block of 2.2.1's revolute K for anchors at arms rA and rB (symmetric, 1/kg).
// Formed on Wide, or on solver::UncheckedWide where a row's bound proves it in range (the same
// bits).
template <class N>
inline b2WideMat22 PointK(const b2Vec2& rA, const b2Vec2& rB, N mA, N mB, N iA, N iB) noexcept {
    const N exx = mA + mB + iA * N(MulWide(rA.y, rA.y)) + iB * N(MulWide(rB.y, rB.y));
    const N exy = -(iA * N(MulWide(rA.x, rA.y))) - iB * N(MulWide(rB.x, rB.y));
    const N eyy = mA + mB + iA * N(MulWide(rA.x, rA.x)) + iB * N(MulWide(rB.x, rB.x));
    b2WideMat22 K;
    K.ex.x = Wide(exx);
    K.ex.y = Wide(exy);
    K.ey.x = K.ex.y;
    K.ey.y = Wide(eyy);
    return K;
}

// The point-to-point position correction (2.2.1's revolute K solve): the impulse that closes
// the gap C between two anchors at arms rA and rB. The solve is always Wide's.
template <class N>
inline b2WideVec2 PointGapImpulse(const b2Vec2& C, const b2Vec2& rA, const b2Vec2& rB, N mA, N mB, N iA,
                                  N iB) noexcept {
    return -PointK(rA, rB, mA, mB, iA, iB).Solve(C);
}

// A revolute K's angular column cannot leave Q32.32 while both inverse inertias are below this
// raw (2^14 per kg m^2): each entry is i r with |r| < 2^15 m. Rows, which read only the point
// block, form the column only at or above it, to report its overflow as 2.2.1's whole K would.
inline constexpr uint64_t kNarrowTurn = uint64_t{1} << 46;

// v.Length() <= limit without the square root, for a limit >= 0. Length rounds sqrt(s) to nearest
// (s the exact squared length), and rounds up exactly when s exceeds r^2 + r for r = floor(sqrt(s));
// so the rounded length is at most L exactly when s <= L^2 + L. The squared length is formed by
// the same call as in Length, so an overflow is reported the same way.
inline bool LengthWithin(const b2Vec2& v, Fixed limit) noexcept {
    const auto s = static_cast<uint64_t>(v.LengthSquaredWide().Raw());
    const auto l = static_cast<uint64_t>(limit.Raw());
    return s <= l * l + l;
}

// 1/k, or 0 for k <= 0 (a constraint between bodies that cannot move).
inline Wide Invert(Wide k) noexcept { return k > Wide() ? Wide(1) / k : Wide(); }

// Soft-constraint coefficients of Box2D 2.2.1 (Catto's soft step), all in Q32.32:
//   omega = 2 pi f, d = 2 m zeta omega, k = m omega^2,
//   gamma = 1 / (h (d + h k)) (1/kg... an inverse effective mass), biasRate = h k gamma (1/s).
// The Q16.16 forms overflow (k = m omega^2 exceeds 32768 for 1000 kg above 0.91 Hz) or
// underflow (h (d + h k)), NUMERICS Table 1.
struct Soft {
    Wide gamma;     // 1/kg (0 when the spring is rigid)
    Wide biasRate;  // 1/s: bias velocity = biasRate * C
};

inline Soft SoftCoefficients(Wide mass, Fixed frequencyHz, Fixed dampingRatio, Fixed h) noexcept {
    Soft s;
    const Fixed omega = math::kTwoPi * frequencyHz;                 // rad/s (<= 188 for 30 Hz)
    const Wide d = mass * MulWide(Fixed(2) * dampingRatio, omega);  // N*s/m
    const Wide k = mass * MulWide(omega, omega);                    // N/m
    const Wide hk = k * h;                                          // N*s/m
    const Wide denom = (d + hk) * h;                                // kg
    s.gamma = Invert(denom);
    s.biasRate = hk * s.gamma;
    return s;
}

}  // namespace lockbox::jointmath
