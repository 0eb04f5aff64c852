#pragma once
/// @file
/// The datagram interface every lockbox session runs on (docs/net.md): send bytes to
/// a peer, poll what arrived, read the clock. Three implementations: SimNet (in memory, seeded,
/// virtual clock; every net test), UdpTransport (POSIX, IPv4 and IPv6) and EnetTransport
/// (libenet: a reliable channel beside the unreliable one).
///
/// The sessions make no assumption about delivery: any datagram may be lost, duplicated,
/// delayed or reordered, and they resend what matters. `Delivery::e_reliable` is a hint that a
/// transport with a reliable channel (ENet) may use; the others send it like any datagram.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/Export.h"

/// The network module: transports (SimNet, UDP, ENet, relayed, latency), the lockstep server
/// and client, and the rollback session, peer and spectator, with their wire protocols.
namespace lockbox::net {

/// A peer as one transport names it: a small index into that transport's peer table. The same
/// remote machine may have different PeerIds on different transports.
using PeerId = uint32_t;
/// "No peer": a PeerId no transport hands out (unset configuration fields, a slot without an
/// owner).
inline constexpr PeerId kNoPeer = 0xFFFFFFFFu;

/// How a datagram should travel. Sessions are correct with either (they resend); reliable only
/// saves resends on a transport that has such a channel.
enum class Delivery : uint8_t {
    e_unreliable = 0,  ///< inputs, acks, hash and quality reports
    e_reliable = 1,    ///< control and snapshot chunks
};

/// One received datagram.
struct Datagram {
    PeerId peer = kNoPeer;       ///< who sent it
    std::vector<uint8_t> bytes;  ///< the payload, as sent
};

/// Counters kept by every transport. `wireBytes*` add the per-datagram overhead of the real
/// medium (IPv4 + UDP headers: 28 bytes; ENet adds its own), so bandwidth budgets are honest.
struct TransportStats {
    uint64_t datagramsSent = 0;      ///< accepted by Send
    uint64_t payloadBytesSent = 0;   ///< payload bytes accepted by Send
    uint64_t wireBytesSent = 0;      ///< payload plus per-datagram header overhead
    uint64_t datagramsReceived = 0;  ///< handed out by Poll
    /// Payload bytes handed out by Poll.
    uint64_t payloadBytesReceived = 0;
    uint64_t sendFailures = 0;    ///< Send returned false (unknown peer, too large, OS error)
    uint64_t droppedUnknown = 0;  ///< received from a sender the transport would not admit
};

/// A datagram transport: unreliable, unordered delivery of payloads of up to MaxDatagram() bytes to
/// peers named by PeerId, plus a microsecond clock (see the file comment). Implementations:
/// SimNet's endpoints, UdpTransport, EnetTransport, RelayedTransport.
class LOCKBOX_API Transport {
public:
    /// Largest payload every transport carries in one datagram (fits a 1280-byte IPv6 MTU).
    static constexpr size_t kMaxDatagram = 1200;

    virtual ~Transport() = default;

    /// Queues one datagram to `peer`. False (and counted) when the peer is unknown, the payload
    /// is empty or larger than MaxDatagram(), or the system refused it.
    virtual bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) = 0;

    /// Appends every datagram that has arrived to `out` and returns how many were appended.
    /// Never blocks.
    virtual size_t Poll(std::vector<Datagram>& out) = 0;

    /// Monotonic time in microseconds: virtual for SimNet, the steady clock for sockets.
    virtual uint64_t NowMicros() const = 0;

    /// The largest payload Send accepts.
    virtual size_t MaxDatagram() const noexcept { return kMaxDatagram; }

    /// Counters since construction.
    virtual const TransportStats& Stats() const noexcept = 0;

    /// Forgets `peer` (closes its connection where there is one). Later datagrams from the same
    /// address may come back under a new PeerId.
    virtual void Disconnect(PeerId peer) { (void)peer; }
};

}  // namespace lockbox::net
