#pragma once
/// @file
/// LatencyTransport (docs/net.md "LatencyTransport"): a decorator over any Transport that
/// impairs what it receives with seeded latency, jitter, loss, duplication and reordering, so
/// a game can test its netcode on real sockets (or on SimNet) with a long cable between peers.
/// Wrap both ends to impair both directions.
///
/// Each datagram the inner transport's Poll hands over, at time t on the inner clock, draws in
/// this order from one generator seeded with `seed`:
///  1. loss (lossPermille): dropped;
///  2. due time = t + latencyMicros + uniform jitter in [0, jitterMicros];
///  3. reorder (reorderPermille): held reorderDelayMicros longer, so later datagrams pass it;
///  4. duplicate (duplicatePermille): a copy with its own jitter draw.
/// Poll hands out every held datagram whose due time has come, in the order (due time,
/// arrival number). All draws are integers: the same seed and the same arrivals at the same
/// clock readings give the same deliveries, bit for bit. Sends pass through untouched.

#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Transport.h"

namespace lockbox::net {

/// The impairments. Rates are per mille (values above 1000 act as 1000: always).
struct LatencyProfile {
    uint32_t latencyMicros = 0;           ///< fixed delay added to every datagram
    uint32_t jitterMicros = 0;            ///< extra delay, uniform in [0, jitterMicros]
    uint32_t lossPermille = 0;            ///< chance a datagram is dropped
    uint32_t duplicatePermille = 0;       ///< chance a datagram is delivered twice
    uint32_t reorderPermille = 0;         ///< chance a datagram is held back by reorderDelayMicros
    uint32_t reorderDelayMicros = 20000;  ///< hold-back of a reordered datagram
};

/// What the decorator did. Every datagram in `received` ends in exactly one of delivered,
/// lost or forgotten, or is still held; a duplicate adds one to `duplicated` and its copy
/// ends the same way.
struct LatencyStats {
    uint64_t received = 0;    ///< handed over by the inner transport
    uint64_t delivered = 0;   ///< handed out by Poll (copies included)
    uint64_t lost = 0;        ///< dropped by the loss draw
    uint64_t duplicated = 0;  ///< datagrams that got a copy
    uint64_t reordered = 0;   ///< datagrams held back by the reorder draw
    uint64_t forgotten = 0;   ///< held ones dropped by Disconnect (copies included)
};

/// A Transport decorator that delays, drops, duplicates and reorders what the inner transport
/// receives, by seeded integer draws (see the file comment); sends pass through. Wrap both ends to
/// impair both directions.
class LOCKBOX_API LatencyTransport final : public Transport {
public:
    /// `inner` must outlive the decorator. Any seed is valid (print it when a test fails).
    LatencyTransport(Transport& inner, LatencyProfile profile, uint64_t seed);

    /// Passes straight to the inner transport.
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override;
    /// Polls the inner transport, draws the fate of what arrived, then appends every held
    /// datagram that is due.
    size_t Poll(std::vector<Datagram>& out) override;
    /// The inner transport's clock.
    uint64_t NowMicros() const override { return m_inner.NowMicros(); }
    /// The inner transport's.
    size_t MaxDatagram() const noexcept override { return m_inner.MaxDatagram(); }
    /// The inner transport's counters, except that the received ones count what this
    /// decorator handed out.
    const TransportStats& Stats() const noexcept override;
    /// Forgets the held datagrams of `peer` and disconnects it on the inner transport.
    void Disconnect(PeerId peer) override;

    /// Changes the impairments for datagrams that arrive from now on (held ones keep theirs).
    void SetProfile(const LatencyProfile& profile) noexcept { m_profile = profile; }
    /// The impairments applied to datagrams arriving now.
    const LatencyProfile& Profile() const noexcept { return m_profile; }
    /// Due time of the earliest held datagram, UINT64_MAX when none is held: a loop may sleep
    /// until then.
    uint64_t NextDueMicros() const noexcept;
    /// Datagrams held and not yet due.
    size_t Held() const noexcept { return m_held.size(); }
    /// What the decorator did to the datagrams it received (counts since construction).
    const LatencyStats& Impairments() const noexcept { return m_impairments; }
    /// The seed the decorator was made with.
    uint64_t Seed() const noexcept { return m_seed; }

private:
    uint64_t Draw() noexcept;
    bool Chance(uint32_t permille) noexcept;
    uint64_t Jitter() noexcept;

    Transport& m_inner;
    LatencyProfile m_profile;
    uint64_t m_seed;
    uint64_t m_state;        // splitmix64 state
    uint64_t m_arrival = 0;  // arrival number: breaks ties of equal due times by order of arrival
    std::map<std::pair<uint64_t, uint64_t>, Datagram> m_held;  // (due, arrival number) -> datagram
    std::vector<Datagram> m_inbox;
    LatencyStats m_impairments;
    uint64_t m_deliveredBytes = 0;
    mutable TransportStats m_stats;
};

}  // namespace lockbox::net
