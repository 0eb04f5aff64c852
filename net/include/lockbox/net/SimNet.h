#pragma once
/// @file
/// SimNet: an in-memory network for tests (docs/net.md "SimNet"). Endpoints live in
/// one process, time is a virtual clock that only the test advances, and every link between
/// two endpoints has its own seeded impairments. The same seed and the same calls give the
/// same deliveries, bit for bit, so a failing test reproduces from its seed.
///
/// Addressing: an endpoint's PeerId for another endpoint is that endpoint's index in the net
/// (AddEndpoint order); a received datagram names its sender the same way.
///
/// The path of one datagram sent at virtual time t on the link from -> to:
///  1. the sender is down: lost (LinkStats::downDropped);
///  2. t lies in a blackout window of the link: dropped (blackoutDropped);
///  3. bandwidth cap: the datagram's wire size (payload + kWireOverhead) joins the link's
///     queue; it is tail-dropped (queueDropped) when the bytes still waiting plus its own would
///     exceed queueLimitBytes (an idle link always takes one), else it has left the link once
///     every byte before it and its own has been sent at bandwidthBitsPerSecond;
///  4. Bernoulli loss, then Gilbert-Elliott burst loss (lost);
///  5. due time = time it left the queue + latency + uniform jitter in [0, jitter], plus
///     reorderDelayMicros when the reorder draw hits (reordered); a duplicate (duplicated) gets
///     its own jitter draw;
///  6. Poll of the receiver hands it out once the clock has reached its due time, in the order
///     (due time, send sequence number); if the receiver is down when it is due, it is dropped
///     (downDropped).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Transport.h"

namespace lockbox::net {

/// Impairments of one direction of one link. Probabilities are in parts per million so the
/// model has no floating point and draws from one seeded integer generator. Values above
/// 1,000,000 ppm act as 1,000,000 (always).
struct LinkProfile {
    uint32_t latencyMicros = 0;  ///< fixed one-way delay
    uint32_t jitterMicros = 0;   ///< extra delay, uniform in [0, jitterMicros]
    uint32_t lossPpm = 0;        ///< Bernoulli loss per datagram
    /// Gilbert-Elliott burst loss: per-datagram chance to enter / leave the bad state, and the
    /// loss inside it. All zero: no bursts. The mean length of a bad period is
    /// 1e6 / burstLeavePpm datagrams.
    ///@{
    uint32_t burstEnterPpm = 0;
    uint32_t burstLeavePpm = 0;
    uint32_t burstLossPpm = 0;
    ///@}
    uint32_t duplicatePpm = 0;  ///< chance a datagram is delivered twice
    uint32_t reorderPpm = 0;    ///< chance a datagram is held back by reorderDelayMicros
    /// How long a reordered datagram is held back, microseconds (added to its due time).
    uint32_t reorderDelayMicros = 0;
    /// 0: unlimited; else wire bytes queue at this rate. Valid range 1 .. 1e12 (1 Tbit/s);
    /// larger values act as 1e12.
    uint64_t bandwidthBitsPerSecond = 0;
    uint32_t queueLimitBytes = 65536;  ///< with a bandwidth cap: tail drop beyond this backlog
};

/// What happened on one direction of one link. Every datagram accepted by Send on the link
/// counts once in `sent` and `wireBytes`, then ends in exactly one of delivered, lost,
/// queueDropped, blackoutDropped, downDropped, or is still in flight; a duplicate adds one to
/// `duplicated` and its copy later counts in delivered or downDropped too.
struct LinkStats {
    uint64_t sent = 0;             ///< datagrams accepted by Send on this link
    uint64_t delivered = 0;        ///< handed out by the receiver's Poll (duplicates included)
    uint64_t lost = 0;             ///< Bernoulli or burst loss
    uint64_t duplicated = 0;       ///< datagrams that got a second copy
    uint64_t reordered = 0;        ///< datagrams held back by reorderDelayMicros
    uint64_t queueDropped = 0;     ///< tail drops of the bandwidth queue
    uint64_t blackoutDropped = 0;  ///< sent during a blackout window
    uint64_t wireBytes = 0;        ///< payload + kWireOverhead of every datagram in `sent`
    uint64_t downDropped = 0;      ///< the sender was down at send, or the receiver at arrival
};

class SimEndpoint;

/// The in-memory network: endpoints (each a Transport), seeded per-link impairments and a virtual
/// clock that only the test advances (see the file comment). Deterministic: the same seed and calls
/// give the same deliveries.
class LOCKBOX_API SimNet {
public:
    /// IPv4 + UDP header bytes added to every payload for wire sizes and wire byte counters.
    static constexpr uint32_t kWireOverhead = 28;

    /// `seed` drives every random draw (one generator per link, derived from the seed and the
    /// link's endpoints, so adding a link does not change the draws of another).
    explicit SimNet(uint64_t seed);
    /// Frees every endpoint and every datagram in flight.
    ~SimNet();
    SimNet(const SimNet&) = delete;
    SimNet& operator=(const SimNet&) = delete;

    /// A new endpoint; its PeerId for every other endpoint is the returned endpoint's Index().
    /// The reference stays valid for the net's lifetime.
    SimEndpoint& AddEndpoint();
    /// The endpoint with that index; throws std::out_of_range when there is none.
    SimEndpoint& Endpoint(PeerId index);
    /// Endpoints added so far.
    size_t EndpointCount() const noexcept;

    /// Sets the impairments of the direction from -> to (default: a perfect link). Keeps the
    /// link's generator, statistics and queue state. Throws std::out_of_range for an unknown
    /// endpoint or from == to.
    void SetLink(PeerId from, PeerId to, const LinkProfile& profile);
    /// Sets both directions between every pair of endpoints, present and future.
    void SetAllLinks(const LinkProfile& profile);
    /// Drops everything sent on from -> to while the clock is in [startMicros, endMicros).
    /// Throws std::out_of_range for an unknown endpoint or from == to.
    void Blackout(PeerId from, PeerId to, uint64_t startMicros, uint64_t endMicros);

    /// The virtual clock in microseconds, starting at 0.
    uint64_t NowMicros() const noexcept;
    /// Moves the clock forward (saturating at UINT64_MAX); datagrams due by then become
    /// visible to Poll, or are dropped if their receiver is down.
    void Advance(uint64_t micros);
    /// The earliest due time of any datagram in flight, or UINT64_MAX when none is. Lets a test
    /// jump the clock straight to the next arrival.
    uint64_t NextDueMicros() const noexcept;
    /// Datagrams sent and not yet handed out or dropped, over all endpoints.
    size_t InFlight() const noexcept;

    /// Statistics of from -> to; all zero for a link that never carried anything.
    const LinkStats& Link(PeerId from, PeerId to) const;
    /// The seed the net was made with (print it when a test fails).
    uint64_t Seed() const noexcept;

private:
    friend class SimEndpoint;
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// One endpoint of a SimNet: a Transport whose clock is the net's virtual clock.
class LOCKBOX_API SimEndpoint : public Transport {
public:
    /// False (counted in sendFailures) when `peer` is not another endpoint of the net or the
    /// size is not in [1, MaxDatagram()]. A datagram from a down endpoint is accepted (true)
    /// and silently lost, like a send from an unplugged machine.
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override;
    /// Appends every datagram due by the current virtual time; none while down.
    size_t Poll(std::vector<Datagram>& out) override;
    /// The net's virtual clock (microseconds since the net was made).
    uint64_t NowMicros() const override;
    /// This endpoint's counters; wireBytesSent adds kWireOverhead per datagram.
    const TransportStats& Stats() const noexcept override { return m_stats; }
    /// The PeerId other endpoints use for this one.
    PeerId Index() const noexcept { return m_index; }
    /// While down, the endpoint neither sends nor receives (a crashed or unplugged machine).
    /// Going down also drops what had arrived and was not polled yet.
    void SetDown(bool down) noexcept;
    /// True while SetDown(true) is in force.
    bool IsDown() const noexcept { return m_down; }

private:
    friend class SimNet;
    friend struct SimNet::Impl;
    SimEndpoint(SimNet::Impl& net, PeerId index) : m_net(&net), m_index(index) {}
    SimNet::Impl* m_net;
    PeerId m_index;
    bool m_down = false;
    TransportStats m_stats;
};

}  // namespace lockbox::net
