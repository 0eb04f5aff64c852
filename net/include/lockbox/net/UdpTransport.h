#pragma once
/// @file
/// UdpTransport: plain POSIX UDP behind the Transport interface (docs/net.md). One
/// non-blocking socket, IPv4 or IPv6 (chosen by the bind address), a fixed-size peer table,
/// the steady clock. No connection, no resend, no reliability: `Delivery` is ignored, as the
/// sessions resend what matters.
///
/// Peers come from AddPeer (addresses we talk to first) or from the first datagram an unknown
/// address sends (a server's clients), as long as the table has a free slot.

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Transport.h"

namespace lockbox::net {

/// Plain POSIX UDP (IPv4 or IPv6) behind the Transport interface: one non-blocking socket, a fixed
/// peer table, the steady clock; no reliability of its own (see the file comment).
class LOCKBOX_API UdpTransport final : public Transport {
public:
    /// Most datagrams one Poll reads before returning, so one call never starves the caller.
    static constexpr size_t kMaxPollPerCall = 1024;
    /// IPv4 + UDP header bytes added to wireBytesSent per datagram.
    static constexpr uint64_t kIpv4Overhead = 28;
    /// IPv6 + UDP header bytes added to wireBytesSent per datagram.
    static constexpr uint64_t kIpv6Overhead = 48;

    /// Opens a non-blocking UDP socket bound to `bindHost` (a numeric address: "127.0.0.1",
    /// "::1", "0.0.0.0", "::"; empty means "0.0.0.0") and `port` (0: an ephemeral port, see
    /// LocalPort()). An IPv6 socket also accepts IPv4-mapped peers when bound to "::".
    /// `maxPeers` (1 .. 65536) bounds the peer table. Returns nullptr and, when `error` is not
    /// null, a message on failure (bad address, port in use, no IPv6 on this machine).
    static std::unique_ptr<UdpTransport> Open(const std::string& bindHost, uint16_t port, std::string* error,
                                              size_t maxPeers = 64);

    /// Closes the socket.
    ~UdpTransport() override;
    UdpTransport(const UdpTransport&) = delete;
    UdpTransport& operator=(const UdpTransport&) = delete;

    /// The port the socket is bound to (the chosen one when Open was given 0).
    uint16_t LocalPort() const noexcept { return m_localPort; }
    /// True for an IPv6 socket.
    bool IsIpv6() const noexcept { return m_ipv6; }

    /// Registers the numeric address `host` ("127.0.0.1", "::1") and `port` (1 .. 65535) as a
    /// peer and returns its PeerId; an address already known returns its existing PeerId.
    /// Returns kNoPeer with a message in `error` (when not null) if the address does not parse,
    /// does not fit the socket's family, or the table is full.
    PeerId AddPeer(const std::string& host, uint16_t port, std::string* error);

    /// "host:port" ("[host]:port" for IPv6) of a known peer, or an empty string.
    std::string PeerAddress(PeerId peer) const;
    /// Number of peers in the table.
    size_t PeerCount() const noexcept { return m_byAddress.size(); }

    /// Sends one datagram with sendto. False (counted in sendFailures) for an unknown peer, a
    /// size outside [1, MaxDatagram()], or when the kernel refuses it (full buffer included).
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override;
    /// Reads datagrams until the socket has none (at most kMaxPollPerCall per call). A sender
    /// not in the table gets a new PeerId while the table has room, else its datagram is dropped
    /// and counted in droppedUnknown. Empty or oversized datagrams are dropped and counted in
    /// DroppedMalformed().
    size_t Poll(std::vector<Datagram>& out) override;
    /// The steady clock in microseconds.
    uint64_t NowMicros() const override;
    /// Counters; wireBytesSent adds kIpv4Overhead or kIpv6Overhead per datagram, by the family
    /// on the wire (an IPv4-mapped peer counts as IPv4).
    const TransportStats& Stats() const noexcept override { return m_stats; }
    /// Frees the peer's slot; its next datagram makes it a new peer (maybe with another id).
    void Disconnect(PeerId peer) override;

    /// Waits up to `timeoutMillis` (0 .. 60,000) for the socket to become readable; true when it
    /// is. For loops that would rather sleep than spin; never needed for correctness.
    bool WaitReadable(int timeoutMillis) const;
    /// Received datagrams dropped because they were empty or larger than MaxDatagram().
    uint64_t DroppedMalformed() const noexcept { return m_droppedMalformed; }

private:
    struct Slot;
    UdpTransport(int fd, bool ipv6, uint16_t localPort, size_t maxPeers);
    PeerId Admit(const void* addr, uint32_t len);

    int m_fd;
    bool m_ipv6;
    uint16_t m_localPort;
    std::vector<Slot> m_slots;
    std::map<std::string, PeerId> m_byAddress;  // key: family, port and address bytes
    std::vector<uint8_t> m_buffer;
    TransportStats m_stats;
    uint64_t m_droppedMalformed = 0;
};

}  // namespace lockbox::net
