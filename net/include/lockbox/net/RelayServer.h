#pragma once
/// @file
/// RelayServer (docs/rollback.md "Relayed matches"): forwards datagrams between the
/// members of one match. A member claims its slot with a token (RelayWire.h join); from then
/// on the relay knows the member by its PeerId on the relay's transport and forwards what it
/// addresses to another slot, stamped with the sender's slot. The relay never reads the
/// payloads: any session (RollbackPeer, a spectator, even the lockstep codec) runs over it
/// unchanged through RelayedTransport.
///
/// A member that joins again with the same token (a new address after a NAT rebinding, a
/// restarted client) takes its slot back; the old address is forgotten. A join with a wrong
/// token, a datagram from a PeerId that holds no slot, one for another match, to an empty slot
/// or to the sender itself is refused and counted, never forwarded.

#include <cstdint>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/RelayWire.h"
#include "lockbox/net/Transport.h"

namespace lockbox::net {

/// Settings of a relay.
struct RelayServerConfig {
    /// The match this relay serves; datagrams with another match id are refused.
    uint32_t matchId = 1;
    /// One secret per slot (slot i is claimed with tokens[i]); 2 .. kRelayMaxSlots entries.
    /// Tokens are handed out by the matchmaker; 0 is a valid token but a poor secret.
    std::vector<uint64_t> tokens;
};

/// Counters of a relay.
struct RelayServerStats {
    uint64_t joins = 0;           ///< valid joins answered (repeats included)
    uint64_t rebinds = 0;         ///< a slot moved to a new PeerId
    uint64_t forwarded = 0;       ///< datagrams forwarded
    uint64_t forwardedBytes = 0;  ///< payload bytes forwarded
    uint64_t refused = 0;         ///< malformed, wrong match, bad token, unknown sender, bad slot
    uint64_t sendFailures = 0;    ///< the transport refused a forward or a welcome
};

/// Forwards opaque datagrams between the members of one match, each known by the slot its token
/// claims (see the file comment). Non-blocking: call Poll often.
class LOCKBOX_API RelayServer {
public:
    /// `transport` must outlive the relay. Throws std::invalid_argument when the slot count is
    /// outside 2 .. kRelayMaxSlots.
    RelayServer(Transport& transport, RelayServerConfig config);

    /// Reads every datagram that arrived and forwards or answers it. Call often (every tick or
    /// faster): the relay adds no delay beyond the time between two Polls.
    void Poll();

    /// The PeerId holding slot `slot`, or kNoPeer.
    PeerId SlotPeer(uint32_t slot) const noexcept;
    /// Frees the slot `peer` holds, if any: nothing more is forwarded to it, and its next valid
    /// join may claim any slot. For a host that learned the member is gone (its address now
    /// belongs to another client). Returns the slot freed, or -1.
    int Release(PeerId peer) noexcept;
    /// Counters since construction.
    const RelayServerStats& Stats() const noexcept { return m_stats; }

private:
    /// The slot bound to `peer`, or -1.
    int SlotOf(PeerId peer) const noexcept;
    void Handle(const Datagram& d);

    Transport& m_transport;
    RelayServerConfig m_config;
    std::vector<PeerId> m_slotPeer;  // slot -> PeerId (kNoPeer when free)
    std::vector<Datagram> m_inbox;
    std::vector<uint8_t> m_out;
    RelayServerStats m_stats;
};

}  // namespace lockbox::net
