#pragma once
/// @file
/// RelayedTransport (docs/rollback.md "Relayed matches"): a Transport that reaches
/// the other members of a match through a RelayServer. It wraps the transport that reaches the
/// relay; the other members appear as PeerIds equal to their slot numbers, so a RollbackPeer
/// (or any session) configured with remotes {slot j} runs unchanged over a relay.
///
/// It joins on construction and repeats the join (every joinRetryMicros, from Send and Poll)
/// until the relay's welcome arrives; datagrams sent before that may be refused by the relay
/// and are resent by the sessions like any lost datagram. Each payload costs the 9-byte relay
/// header: MaxDatagram() is the inner transport's minus 9.

#include <cstdint>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/RelayWire.h"
#include "lockbox/net/Transport.h"

namespace lockbox::net {

/// Settings of a relayed member.
struct RelayedTransportConfig {
    PeerId relay = kNoPeer;  ///< the relay's PeerId on the inner transport
    /// The match id, the same for every member and the relay.
    uint32_t matchId = 1;
    uint32_t slot = 0;                  ///< this member's slot, < slots
    uint32_t slots = 2;                 ///< the relay's slot count, 2 .. kRelayMaxSlots
    uint64_t token = 0;                 ///< this slot's secret
    uint64_t joinRetryMicros = 100000;  ///< join resend interval until welcomed, >= 1
};

/// A Transport to the other members of a match through a RelayServer: the members appear as PeerIds
/// equal to their slots, so any session runs over a relay unchanged (see the file comment).
class LOCKBOX_API RelayedTransport final : public Transport {
public:
    /// `inner` must outlive this transport. Throws std::invalid_argument for a slot outside
    /// [0, slots), slots outside 2 .. kRelayMaxSlots, no relay or a zero retry interval.
    RelayedTransport(Transport& inner, RelayedTransportConfig config);

    /// `peer` is the destination slot. False (counted) for its own slot, a slot outside the
    /// match, an empty payload or one larger than MaxDatagram(), or when the inner send fails.
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override;
    /// Datagrams forwarded by the relay, each with peer = the sender's slot. Anything else
    /// (other senders, other matches, malformed) is dropped and counted in droppedUnknown.
    size_t Poll(std::vector<Datagram>& out) override;
    uint64_t NowMicros() const override { return m_inner.NowMicros(); }
    size_t MaxDatagram() const noexcept override { return m_inner.MaxDatagram() - kRelayHeaderBytes; }
    /// Payload counters of the relayed links; wireBytesSent adds the relay header (the inner
    /// transport's own counters add the medium's).
    const TransportStats& Stats() const noexcept override { return m_stats; }

    /// True once the relay has welcomed this member.
    bool Joined() const noexcept { return m_joined; }

private:
    void MaybeJoin();

    Transport& m_inner;
    RelayedTransportConfig m_config;
    bool m_joined = false;
    bool m_joinSent = false;
    uint64_t m_lastJoin = 0;
    std::vector<uint8_t> m_out;
    std::vector<Datagram> m_inbox;
    TransportStats m_stats;
};

}  // namespace lockbox::net
