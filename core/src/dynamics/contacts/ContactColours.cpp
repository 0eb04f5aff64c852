// Greedy colouring of an island's contacts and the counting sort into colour order.
#include "dynamics/contacts/ContactColours.h"

#include <algorithm>
#include <bit>

#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

void b2ContactColours::Order(b2Contact** contacts, int32 count, int32 slotCount) {
    const auto n = static_cast<size_t>(count);
    m_masks.assign(static_cast<size_t>(slotCount), 0u);
    if (m_colours.size() < n) {
        m_colours.resize(n);
        m_ordered.resize(n);
    }
    // The solver slot of a body the contact solver writes, or -1.
    auto writtenSlot = [](const b2Body* body) { return body->m_type == b2_dynamicBody ? body->m_islandIndex : -1; };
    std::array<int32, kColourCount + 1> sizes{};
    for (size_t i = 0; i < n; ++i) {
        const b2Contact* contact = contacts[i];
        const int32 a = writtenSlot(contact->m_fixtureA->m_body);
        const int32 b = writtenSlot(contact->m_fixtureB->m_body);
        uint32 taken = 0;
        if (a >= 0) taken |= m_masks[static_cast<size_t>(a)];
        if (b >= 0) taken |= m_masks[static_cast<size_t>(b)];
        const int colour = std::countr_one(taken);  // kColourCount or more: every colour taken
        if (colour < kColourCount) {
            const uint32 bit = uint32{1} << colour;
            if (a >= 0) m_masks[static_cast<size_t>(a)] |= bit;
            if (b >= 0) m_masks[static_cast<size_t>(b)] |= bit;
            m_colours[i] = static_cast<uint8>(colour);
        } else {
            m_colours[i] = static_cast<uint8>(kColourCount);
        }
        ++sizes[m_colours[i]];
    }
    m_starts[0] = 0;
    for (int32 c = 0; c <= kColourCount; ++c)
        m_starts[static_cast<size_t>(c) + 1] = m_starts[static_cast<size_t>(c)] + sizes[static_cast<size_t>(c)];
    std::array<int32, kColourCount + 1> next{};
    std::copy_n(m_starts.begin(), kColourCount + 1, next.begin());
    for (size_t i = 0; i < n; ++i) m_ordered[static_cast<size_t>(next[m_colours[i]]++)] = contacts[i];
    std::copy_n(m_ordered.begin(), n, contacts);
}

}  // namespace lockbox
