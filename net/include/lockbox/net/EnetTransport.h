#pragma once
/// @file
/// EnetTransport: the Transport interface over ENet 1.3.17 (Debian libenet-dev), for the
/// lockstep server (docs/net.md). One UDP socket, IPv4 only (an ENet 1.3 limit), and
/// two channels per connection:
///  - channel 0, reliable and ordered (Delivery::e_reliable): control and snapshot chunks;
///  - channel 1, unsequenced and unreliable (Delivery::e_unreliable): inputs, acks, reports.
///
/// ENet's packet throttle drops outgoing unreliable packets when it thinks the RTT is rising.
/// Every connection is configured (both ends, on connect) with acceleration = the throttle
/// scale and deceleration = 0, so its throttle stays at ENET_PEER_PACKET_THROTTLE_SCALE and
/// the check `counter (0..31) > throttle (32)` never drops an input. Every host is created
/// with no bandwidth limit (incoming and outgoing 0), so ENet's bandwidth throttle keeps the
/// throttle limit at the scale too; a foreign ENet peer that declares an incoming bandwidth
/// could still lower it. The MTU is 1372 (as 0 A.D. does), so every datagram up to
/// kMaxDatagram travels unfragmented.
///
/// Timing is ENet's own wall clock: this transport cannot run on SimNet's virtual clock.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Transport.h"

/// ENet's host and peer types, declared as enet/enet.h declares them so that this header does
/// not pull ENet's header into every user of the transport.
///@{
typedef struct _ENetHost ENetHost;
typedef struct _ENetPeer ENetPeer;
///@}

namespace lockbox::net {

/// The Transport interface over ENet: one IPv4 UDP socket, a reliable ordered channel for
/// Delivery::e_reliable and an unreliable one for the rest, ENet's wall clock (see the file
/// comment).
class LOCKBOX_API EnetTransport final : public Transport {
public:
    /// ENet channel of Delivery::e_reliable datagrams (reliable, ordered).
    static constexpr uint8_t kReliableChannel = 0;
    /// ENet channel of Delivery::e_unreliable datagrams (ENET_PACKET_FLAG_UNSEQUENCED).
    static constexpr uint8_t kUnreliableChannel = 1;
    /// The MTU set on the host and every peer (bytes of one UDP payload ENet builds).
    static constexpr uint32_t kMtu = 1372;
    /// Bytes added to wireBytesSent per datagram: IPv4 + UDP (28), ENet's protocol header with
    /// its sent time (4) and the largest send command header, unsequenced (8). ENet may pack
    /// several commands into one UDP datagram and adds acks of its own, so this is an estimate
    /// of the per-datagram cost when each datagram travels alone, as inputs do.
    static constexpr uint64_t kWireOverhead = 28 + 4 + 8;
    /// Most events one Poll handles before returning.
    static constexpr size_t kMaxEventsPerPoll = 4096;
    /// Datagrams Send queues for a peer that is still connecting (flushed, in order, when it
    /// connects); beyond this Send fails and counts.
    static constexpr size_t kMaxPendingPerPeer = 256;
    /// Largest peer table (ENet's protocol limit is 4095 peers per host).
    static constexpr size_t kMaxPeersLimit = 4095;

    /// A server host bound to `bindHost` (numeric IPv4, default 127.0.0.1; "0.0.0.0" for every
    /// interface) and `port` (0: an ephemeral port, read back with LocalPort()), accepting up to
    /// `maxPeers` (1 .. 4095) connections. Returns nullptr with a message in `error` (when not
    /// null) on failure (bad address, port in use, ENet failed to initialize).
    static std::unique_ptr<EnetTransport> Listen(uint16_t port, size_t maxPeers, std::string* error,
                                                 const std::string& bindHost = "127.0.0.1");
    /// A client host (ephemeral port, accepts no connection) that can Connect to up to
    /// `maxPeers` (1 .. 4095) servers. Returns nullptr with a message on failure.
    static std::unique_ptr<EnetTransport> Client(std::string* error, size_t maxPeers = 4);

    /// Sends every peer an immediate disconnect, then destroys the host.
    ~EnetTransport() override;
    EnetTransport(const EnetTransport&) = delete;
    EnetTransport& operator=(const EnetTransport&) = delete;

    /// Starts connecting to the numeric IPv4 address `host` and `port` (1 .. 65535). Returns
    /// the peer's id at once; Send may be used before the connection is up (datagrams wait,
    /// see kMaxPendingPerPeer). The connection is up once IsConnected() says so (seen in Poll).
    /// Returns kNoPeer with a message in `error` if the address does not parse or no slot is
    /// free. A connection that never comes up ends like a disconnect (TakeDisconnected).
    PeerId Connect(const std::string& host, uint16_t port, std::string* error);

    /// The UDP port the host is bound to (0 for a client before its first send).
    uint16_t LocalPort() const noexcept;
    /// True once the connection with `peer` is established and until it ends.
    bool IsConnected(PeerId peer) const noexcept;
    /// ENet's mean RTT estimate for `peer` in milliseconds (0 for an unknown peer).
    uint32_t RoundTripMillis(PeerId peer) const noexcept;
    /// ENet's current unreliable packet throttle for `peer` (ENET_PEER_PACKET_THROTTLE_SCALE,
    /// 32, means nothing is dropped; 0 for an unknown peer). For tests of the configuration.
    uint32_t PacketThrottle(PeerId peer) const noexcept;

    /// Peers whose connection came up (for a server: new clients) since the last call, in the
    /// order ENet reported them.
    std::vector<PeerId> TakeConnected();
    /// Peers whose connection ended (remote disconnect, timeout, failed connect) since the last
    /// call. Their ids are free again.
    std::vector<PeerId> TakeDisconnected();

    /// Queues one datagram on channel 0 (reliable) or 1 (unsequenced) and flushes the host, so
    /// it leaves now. False (counted in sendFailures) for an unknown peer, a size outside
    /// [1, MaxDatagram()], a full pending queue, or when ENet refuses it.
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override;
    /// Services the host without waiting until it reports no event (at most kMaxEventsPerPoll):
    /// connects and disconnects update the peer table, received packets are appended. Packets
    /// from a peer no longer in the table are dropped (droppedUnknown); empty or oversized ones
    /// too (DroppedMalformed()). A server with a full table refuses new connections
    /// (droppedUnknown).
    size_t Poll(std::vector<Datagram>& out) override;
    /// The steady clock in microseconds.
    uint64_t NowMicros() const override;
    /// Counters; wireBytesSent adds kWireOverhead per datagram.
    const TransportStats& Stats() const noexcept override { return m_stats; }
    /// Starts a graceful disconnect of `peer` and frees its id at once; the remote sees a
    /// disconnect event. Unknown ids are ignored.
    void Disconnect(PeerId peer) override;

    /// Waits up to `timeoutMillis` (0 .. 60,000) for the socket to have something to read;
    /// true when it does. For loops that would rather sleep than spin.
    bool WaitReadable(int timeoutMillis) const;
    /// Received packets dropped because they were empty or larger than MaxDatagram().
    uint64_t DroppedMalformed() const noexcept { return m_droppedMalformed; }

private:
    struct Slot;
    EnetTransport(ENetHost* host, size_t maxPeers);
    PeerId FreeSlot() const noexcept;
    void Bind(PeerId id, ENetPeer* peer);
    void Release(PeerId id);
    void OnConnected(PeerId id);
    bool SendNow(ENetPeer* peer, std::span<const uint8_t> bytes, Delivery delivery);

    ENetHost* m_host;
    std::vector<Slot> m_slots;
    std::vector<PeerId> m_connected, m_disconnected;
    TransportStats m_stats;
    uint64_t m_droppedMalformed = 0;
};

}  // namespace lockbox::net
