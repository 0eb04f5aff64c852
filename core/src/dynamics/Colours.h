#pragma once
// The colour order of a large island's constraints (its contacts, and its joints apart). Two
// constraints of one colour write no body in common, so a colour's constraints may be solved in
// any order, or at the same time, and give the same bits. Solving colour after colour is
// therefore the one order that any number of workers can reproduce; a large island is solved in
// it with every worker count, one included.
//
// Colours are given greedily, in island order: each constraint takes the lowest colour that
// none of the bodies it writes has yet (the solvers write dynamic bodies only). A constraint
// that finds every colour taken, or that must be solved in sequence with others (see the
// island's rules), goes to the overflow set, solved after the colours, one after the other.
// Within a colour, constraints keep island order, except that each run of kRun of them puts its
// items of the first kind (say, contacts of one point) before those of the second: the contact
// lanes then find quads of one kind, and a worker's share of a colour still holds constraints
// near one another in the island. The overflow keeps island order. Every choice depends on the
// island alone.

#include <algorithm>
#include <array>
#include <bit>
#include <vector>

#include "lockbox/common/Settings.h"

namespace lockbox {

/// Colours available before the overflow set (one bit each in a body's mask).
inline constexpr int32 b2_colourCount = 24;
/// Islands with fewer constraints of a kind keep island order for that kind: they are too small
/// to share between workers, and their solve order stays 2.2.1's.
inline constexpr int32 b2_minColouredConstraints = 1024;
/// Whether an island's `count` constraints of one kind are solved in colour order.
constexpr bool b2Coloured(int32 count) noexcept { return count >= b2_minColouredConstraints; }

template <class Item>
class b2Colours {
public:
    /// The solver slots of the bodies an item writes (-1 for none), or false when the item must
    /// be solved in sequence (the overflow).
    struct Written {
        int32 a = -1, b = -1;
        bool colourable = true;
        bool secondKind = false;  ///< within its run of a colour, placed after the first kind
    };

    /// The runs of a colour within which the first kind goes first.
    static constexpr int32 kRun = 128;

    /// Room for a table of what items [0, count) write, entry i for item i. Filling it reads
    /// each item's bodies, which blocks of items may do at the same time, while the colours
    /// themselves must be given in order: with workers, the caller fills it first and Order
    /// reads it.
    Written* Table(int32 count) {
        if (m_written.size() < static_cast<size_t>(count)) m_written.resize(static_cast<size_t>(count));
        return m_written.data();
    }

    /// Reorders items[0, count) into colour order. `written(i)` gives what item i writes: a
    /// Written whose slots lie below slotCount.
    template <class WrittenOf>
    void Order(Item** items, int32 count, int32 slotCount, WrittenOf written) {
        const auto n = static_cast<size_t>(count);
        m_masks.assign(static_cast<size_t>(slotCount), 0u);
        if (m_colours.size() < n) {
            m_colours.resize(n);
            m_ordered.resize(n);
            m_orderedKind.resize(n);
        }
        std::array<int32, b2_colourCount + 1> sizes{};
        for (size_t i = 0; i < n; ++i) {
            const Written w = written(i);
            uint32 taken = 0;
            if (w.a >= 0) taken |= m_masks[static_cast<size_t>(w.a)];
            if (w.b >= 0) taken |= m_masks[static_cast<size_t>(w.b)];
            // b2_colourCount or more: every colour taken.
            const int colour = w.colourable ? std::countr_one(taken) : b2_colourCount;
            if (colour < b2_colourCount) {
                const uint32 bit = uint32{1} << colour;
                if (w.a >= 0) m_masks[static_cast<size_t>(w.a)] |= bit;
                if (w.b >= 0) m_masks[static_cast<size_t>(w.b)] |= bit;
                m_colours[i] = static_cast<uint8>(colour);
            } else {
                m_colours[i] = static_cast<uint8>(b2_colourCount);
            }
            ++sizes[m_colours[i]];
            if (w.secondKind) m_colours[i] |= kSecondKind;
        }
        m_starts[0] = 0;
        for (size_t c = 0; c <= b2_colourCount; ++c) m_starts[c + 1] = m_starts[c] + sizes[c];
        std::array<int32, b2_colourCount + 1> next{};
        std::copy_n(m_starts.begin(), b2_colourCount + 1, next.begin());
        for (size_t i = 0; i < n; ++i) {
            const uint8 entry = m_colours[i];
            const auto at = static_cast<size_t>(next[static_cast<size_t>(entry & ~kSecondKind)]++);
            m_ordered[at] = items[i];
            m_orderedKind[at] = static_cast<uint8>(entry & kSecondKind);
        }
        // Each run of a colour: the first kind, then the second, each in island order.
        for (int32 c = 0; c < b2_colourCount; ++c) {
            for (int32 run = m_starts[c]; run < m_starts[c + 1]; run += kRun) {
                const int32 end = std::min(run + kRun, m_starts[c + 1]);
                int32 out = run;
                for (int32 k = run; k < end; ++k)
                    if (!m_orderedKind[static_cast<size_t>(k)]) items[out++] = m_ordered[static_cast<size_t>(k)];
                for (int32 k = run; k < end; ++k)
                    if (m_orderedKind[static_cast<size_t>(k)]) items[out++] = m_ordered[static_cast<size_t>(k)];
            }
        }
        const auto overflow = static_cast<size_t>(m_starts[b2_colourCount]);
        std::copy(m_ordered.begin() + static_cast<std::ptrdiff_t>(overflow),
                  m_ordered.begin() + static_cast<std::ptrdiff_t>(n), items + overflow);
    }

    /// Colour c holds items [Start(c), Start(c + 1)); colour b2_colourCount is the overflow.
    int32 Start(int32 colour) const noexcept { return m_starts[static_cast<size_t>(colour)]; }

private:
    std::vector<Written> m_written;  ///< per item, in island order: the slots it writes
    std::vector<uint32> m_masks;     ///< per body slot: the colours its constraints took
    /// Marks an item of the second kind in its m_colours entry (colours take the low bits).
    static constexpr uint8 kSecondKind = 0x80;
    static_assert(b2_colourCount < kSecondKind);

    std::vector<uint8> m_colours;      ///< per item, in island order: colour | kSecondKind
    std::vector<Item*> m_ordered;      ///< the items in colour order, before copying back
    std::vector<uint8> m_orderedKind;  ///< per item in colour order: its kSecondKind bit
    std::array<int32, b2_colourCount + 2> m_starts{};
};

}  // namespace lockbox
