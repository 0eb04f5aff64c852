#pragma once
// The colour order of a large island's contacts. Two contacts of one colour share no dynamic
// body, so a colour's contacts may be solved in any order, or at the same time, and give the
// same bits. Solving colour after colour is therefore the one order that any number of workers
// can reproduce; a large island is solved in it with every worker count, one included.
//
// Colours are given greedily, in island order: each contact takes the lowest colour that
// neither of its dynamic bodies has yet (static and kinematic bodies are never written by the
// contact solver, so they do not constrain). A contact that finds every colour taken goes to
// the overflow set, solved after the colours, one contact after the other. Within a colour,
// contacts keep island order. Every choice depends on the island's data only.

#include <array>
#include <vector>

#include "Engine.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

class b2Contact;

class core_detail::Engine::ContactColours {
public:
    /// Colours available before the overflow set (one bit each in a body's mask).
    static constexpr int32 kColourCount = 24;
    /// Islands with fewer contacts keep island order: they are too small to share between
    /// workers, and their solve order stays 2.2.1's.
    static constexpr int32 kMinContacts = 1024;

    /// Reorders contacts[0, count) into colour order. The bodies' solver slots
    /// (b2Body::m_islandIndex) must be set and lie below slotCount.
    void Order(b2Contact** contacts, int32 count, int32 slotCount);

    /// Colour c holds contacts [Start(c), Start(c + 1)); colour kColourCount is the overflow.
    int32 Start(int32 colour) const noexcept { return m_starts[static_cast<size_t>(colour)]; }

private:
    std::vector<uint32> m_masks;        ///< per body slot: the colours its contacts took
    std::vector<uint8> m_colours;       ///< per contact, in island order
    std::vector<b2Contact*> m_ordered;  ///< the contacts in colour order, before copying back
    std::array<int32, kColourCount + 2> m_starts{};
};

using b2ContactColours = core_detail::Engine::ContactColours;

}  // namespace lockbox
