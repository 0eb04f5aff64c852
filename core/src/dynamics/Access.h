#pragma once
// The few internals of bodies and contacts that code outside the engine's nested parts reads
// (Engine.h): named here rather than opened wider.

#include <cstddef>

#include "Engine.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

struct core_detail::Engine::Bodies {
    /// The flag of a body in the simulation (the snapshot checks read a body record's flags).
    static constexpr uint16 kActiveFlag = b2Body::e_activeFlag;
    /// Rotational inertia about the centre of mass, kg*m^2 (headroom telemetry; b2Body's
    /// GetInertia is about the origin).
    static Wide CentralInertia(const b2Body& b) noexcept { return b.m_I; }
    /// Inverse mass, 1/kg, and inverse central inertia, 1/(kg*m^2) (headroom telemetry).
    static Wide InvMass(const b2Body& b) noexcept { return b.m_invMass; }
    static Wide InvInertia(const b2Body& b) noexcept { return b.m_invI; }
};

struct core_detail::Engine::Contacts {
    /// Bytes from a contact's start to its graph edges: what the state walks read of it (the
    /// flags end it and the edges follow them, so the walks can request just these cache lines).
    static size_t WalkedBytes(const b2Contact& c) noexcept {
        return static_cast<size_t>(reinterpret_cast<const char*>(&c.m_nodeA) - reinterpret_cast<const char*>(&c));
    }
};

}  // namespace lockbox
