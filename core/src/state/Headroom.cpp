// Headroom telemetry: one read-only pass over a world's state, recording raw magnitudes.

#include "lockbox/state/Headroom.h"

#include "dynamics/Access.h"
#include "dynamics/WorldState.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"

namespace lockbox {
namespace {

using C = b2HeadroomClass;

// |v| as an unsigned value; the unsigned negation is defined for every input, INT64_MIN included.
constexpr uint64 Mag(int64_t v) noexcept { return v < 0 ? uint64{0} - static_cast<uint64>(v) : static_cast<uint64>(v); }

constexpr uint64 kFixedLimit = static_cast<uint64>(Fixed::kMaxRaw);
constexpr uint64 kWideLimit = static_cast<uint64>(Wide::kMaxRaw);

// GetReactionForce(1/256) returns impulse/256 in Q16.16: raw r stands for r * 256 / 2^16 N*s,
// which is r * 2^24 in Q32.32 raw (|r| < 2^31, so the product stays below 2^55).
constexpr Fixed kJointScale = Fixed::FromRaw(256);  // 1/256, dimensionless (1/s times s)
constexpr int kJointToWideShift = 24;

class Walker {
public:
    explicit Walker(b2Headroom& h) : m_h(h) {}

    void See(C c, int64_t raw) noexcept {
        b2HeadroomEntry& e = m_h[c];
        const uint64 m = Mag(raw);
        if (m > e.maxRaw) e.maxRaw = m;
    }
    void SeeVec(C c, const b2Vec2& v) noexcept {
        See(c, v.x.Raw());
        See(c, v.y.Raw());
    }
    void SeeJointImpulse(int32 raw) noexcept { See(C::e_impulse, static_cast<int64_t>(Mag(raw) << kJointToWideShift)); }

private:
    b2Headroom& m_h;
};

}  // namespace

const char* b2HeadroomClassName(b2HeadroomClass c) noexcept {
    switch (c) {
        case C::e_position: return "position";
        case C::e_angle: return "angle";
        case C::e_velocity: return "velocity";
        case C::e_angularVelocity: return "angular_velocity";
        case C::e_impulse: return "impulse";
        case C::e_mass: return "mass";
        case C::e_inertia: return "inertia";
        case C::e_invMass: return "inv_mass";
        case C::e_invInertia: return "inv_inertia";
        case C::e_treeBounds: return "tree_bounds";
        case C::e_treeCost: return "tree_cost";
        case C::e_count: break;
    }
    return "none";
}

int64_t b2HeadroomEntry::PartsPerMillion() const noexcept {
    if (limit == 0) return 0;
    detail::S128 n;
    n.mag = detail::MulU64(maxRaw, 1000000);  // < 2^64 * 2^20: fits 128 bits
    detail::S128 d;
    d.mag = detail::U128{0, limit};
    // maxRaw <= limit + 1 for every class, so the quotient is at most about 1e6.
    return static_cast<int64_t>(detail::DivRoundS128(n, d).mag.lo);
}

b2Headroom::b2Headroom() noexcept {
    // The format of each class, in b2HeadroomClass order (Q16.16 state, Q32.32 mass
    // properties, impulses and costs).
    const uint64 limits[static_cast<int32>(C::e_count)] = {kFixedLimit, kFixedLimit, kFixedLimit, kFixedLimit,
                                                           kWideLimit,  kWideLimit,  kWideLimit,  kWideLimit,
                                                           kWideLimit,  kFixedLimit, kWideLimit};
    for (int32 i = 0; i < static_cast<int32>(C::e_count); ++i) entries[i].limit = limits[i];
}

void b2Headroom::Merge(const b2Headroom& other) noexcept {
    for (int32 i = 0; i < static_cast<int32>(C::e_count); ++i) {
        if (other.entries[i].maxRaw > entries[i].maxRaw) entries[i].maxRaw = other.entries[i].maxRaw;
    }
    saturations += other.saturations;
}

b2HeadroomClass b2Headroom::Tightest() const noexcept {
    int32 best = 0;
    for (int32 i = 1; i < static_cast<int32>(C::e_count); ++i) {
        // Compare maxRaw_i / limit_i > maxRaw_best / limit_best exactly: both sides are below
        // 2^64 * 2^64, so compare the 128-bit cross products through the fixed layer's helper.
        const detail::U128 lhs = detail::MulU64(entries[i].maxRaw, entries[best].limit);
        const detail::U128 rhs = detail::MulU64(entries[best].maxRaw, entries[i].limit);
        if (lhs.hi > rhs.hi || (lhs.hi == rhs.hi && lhs.lo > rhs.lo)) best = i;
    }
    return static_cast<b2HeadroomClass>(best);
}

b2Headroom b2MeasureHeadroom(const b2World& world) {
    using Bodies = core_detail::Engine::Bodies;
    b2Headroom h;
    Walker w(h);

    for (const b2Body* b = world.GetBodyList(); b != nullptr; b = b->GetNext()) {
        w.SeeVec(C::e_position, b->GetPosition());
        w.SeeVec(C::e_position, b->GetWorldCenter());
        w.See(C::e_angle, b->GetAngle().Raw());
        w.SeeVec(C::e_velocity, b->GetLinearVelocity());
        w.See(C::e_angularVelocity, b->GetAngularVelocity().Raw());
        w.See(C::e_mass, b->GetMass().Raw());
        w.See(C::e_inertia, Bodies::CentralInertia(*b).Raw());
        w.See(C::e_invMass, Bodies::InvMass(*b).Raw());
        w.See(C::e_invInertia, Bodies::InvInertia(*b).Raw());
    }

    for (const b2Contact* c = world.GetContactList(); c != nullptr; c = c->GetNext()) {
        const b2Manifold* m = c->GetManifold();
        for (int32 i = 0; i < m->pointCount; ++i) {
            w.See(C::e_impulse, m->points[i].normalImpulse.Raw());
            w.See(C::e_impulse, m->points[i].tangentImpulse.Raw());
        }
    }

    for (const b2Joint* j = world.GetJointList(); j != nullptr; j = j->GetNext()) {
        const b2Vec2 f = j->GetReactionForce(kJointScale);
        w.SeeJointImpulse(f.x.Raw());
        w.SeeJointImpulse(f.y.Raw());
        w.SeeJointImpulse(j->GetReactionTorque(kJointScale).Raw());
    }

    const b2DynamicTree& tree = core_detail::Engine::Of(world).m_contactManager.m_broadPhase.GetTree();
    const auto& nodes = tree.GetNodes();
    for (const b2TreeNode& n : nodes) {
        if (n.height < 0) continue;  // free slot
        w.SeeVec(C::e_treeBounds, n.aabb.lowerBound);
        w.SeeVec(C::e_treeBounds, n.aabb.upperBound);
    }
    if (tree.GetRoot() != b2_nullNode) {
        // InsertLeaf's largest cost is 2 * perimeter of the root (the root encloses every node).
        const Wide p = nodes[static_cast<size_t>(tree.GetRoot())].aabb.GetPerimeterWide();
        w.See(C::e_treeCost, static_cast<int64_t>(Mag(p.Raw()) > kWideLimit / 2 ? kWideLimit : Mag(p.Raw()) * 2));
    }
    return h;
}

}  // namespace lockbox
