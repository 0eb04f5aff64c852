// UdpTransport: one non-blocking POSIX UDP socket and a fixed peer table.
#include "lockbox/net/UdpTransport.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include "transport/SocketSetup.h"

namespace lockbox::net {

using transport_detail::kSocketBufferBytes;
using transport_detail::SetError;

struct UdpTransport::Slot {
    bool used = false;
    sockaddr_storage addr{};
    socklen_t len = 0;
    std::string key;
};

namespace {

constexpr size_t kMaxPeersLimit = 65536;

std::string Errno(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

// Parses a numeric address with getaddrinfo. `family` AF_UNSPEC accepts either.
bool Resolve(const std::string& host, uint16_t port, int family, bool passive, sockaddr_storage& out, socklen_t& len,
             std::string* error) {
    addrinfo hints{};
    hints.ai_family = family;
    hints.ai_socktype = SOCK_DGRAM;
    hints.ai_flags = AI_NUMERICHOST | AI_NUMERICSERV | (passive ? AI_PASSIVE : 0);
    const std::string service = std::to_string(port);
    addrinfo* result = nullptr;
    const int rc = getaddrinfo(host.empty() ? nullptr : host.c_str(), service.c_str(), &hints, &result);
    if (rc != 0 || result == nullptr) {
        SetError(error, "cannot parse address '" + host + "': " + gai_strerror(rc));
        return false;
    }
    if (result->ai_addrlen > sizeof(out)) {
        freeaddrinfo(result);
        SetError(error, "address too long: " + host);
        return false;
    }
    std::memset(&out, 0, sizeof(out));
    std::memcpy(&out, result->ai_addr, result->ai_addrlen);
    len = static_cast<socklen_t>(result->ai_addrlen);
    freeaddrinfo(result);
    return true;
}

// IPv4 address as seen by an IPv6 socket: ::ffff:a.b.c.d.
void MapToV6(const sockaddr_in& v4, sockaddr_in6& v6) {
    std::memset(&v6, 0, sizeof(v6));
    v6.sin6_family = AF_INET6;
    v6.sin6_port = v4.sin_port;
    v6.sin6_addr.s6_addr[10] = 0xFF;
    v6.sin6_addr.s6_addr[11] = 0xFF;
    std::memcpy(&v6.sin6_addr.s6_addr[12], &v4.sin_addr, 4);
}

// The same bytes for the same sender, whatever padding the kernel leaves in the sockaddr.
std::string AddressKey(const sockaddr_storage& addr) {
    std::string key;
    if (addr.ss_family == AF_INET) {
        const auto& a = reinterpret_cast<const sockaddr_in&>(addr);
        key.push_back('4');
        key.append(reinterpret_cast<const char*>(&a.sin_port), sizeof(a.sin_port));
        key.append(reinterpret_cast<const char*>(&a.sin_addr), sizeof(a.sin_addr));
    } else if (addr.ss_family == AF_INET6) {
        const auto& a = reinterpret_cast<const sockaddr_in6&>(addr);
        key.push_back('6');
        key.append(reinterpret_cast<const char*>(&a.sin6_port), sizeof(a.sin6_port));
        key.append(reinterpret_cast<const char*>(&a.sin6_addr), sizeof(a.sin6_addr));
        key.append(reinterpret_cast<const char*>(&a.sin6_scope_id), sizeof(a.sin6_scope_id));
    }
    return key;
}

bool IsMappedV4(const sockaddr_storage& addr) {
    if (addr.ss_family != AF_INET6) return false;
    const auto& a = reinterpret_cast<const sockaddr_in6&>(addr);
    return IN6_IS_ADDR_V4MAPPED(&a.sin6_addr);
}

}  // namespace

std::unique_ptr<UdpTransport> UdpTransport::Open(const std::string& bindHost, uint16_t port, std::string* error,
                                                 size_t maxPeers) {
    if (maxPeers == 0 || maxPeers > kMaxPeersLimit) {
        SetError(error, "maxPeers must be in 1..65536");
        return nullptr;
    }
    sockaddr_storage addr{};
    socklen_t len = 0;
    if (!Resolve(bindHost.empty() ? "0.0.0.0" : bindHost, port, AF_UNSPEC, true, addr, len, error)) return nullptr;
    const bool ipv6 = addr.ss_family == AF_INET6;
    const int fd = ::socket(addr.ss_family, SOCK_DGRAM, 0);
    if (fd < 0) {
        SetError(error, Errno("socket"));
        return nullptr;
    }
    auto fail = [&](const char* what) {
        SetError(error, Errno(what));
        ::close(fd);
        return nullptr;
    };
    const int flags = ::fcntl(fd, F_GETFL, 0);
    if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) return fail("fcntl(O_NONBLOCK)");
    (void)::fcntl(fd, F_SETFD, FD_CLOEXEC);
    if (ipv6) {
        // Dual stack on "::" so IPv4 peers reach an IPv6 server; harmless on a specific address.
        const int off = 0;
        (void)::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &off, sizeof(off));
    }
    const int bufferBytes = kSocketBufferBytes;
    (void)::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &bufferBytes, sizeof(bufferBytes));
    (void)::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &bufferBytes, sizeof(bufferBytes));
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), len) != 0) return fail("bind");
    sockaddr_storage bound{};
    socklen_t boundLen = sizeof(bound);
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &boundLen) != 0) return fail("getsockname");
    const uint16_t localPort = ntohs(ipv6 ? reinterpret_cast<const sockaddr_in6&>(bound).sin6_port
                                          : reinterpret_cast<const sockaddr_in&>(bound).sin_port);
    return std::unique_ptr<UdpTransport>(new UdpTransport(fd, ipv6, localPort, maxPeers));
}

UdpTransport::UdpTransport(int fd, bool ipv6, uint16_t localPort, size_t maxPeers)
    : m_fd(fd), m_ipv6(ipv6), m_localPort(localPort), m_slots(maxPeers), m_buffer(65536) {}

UdpTransport::~UdpTransport() {
    if (m_fd >= 0) ::close(m_fd);
}

PeerId UdpTransport::Admit(const void* addr, uint32_t len) {
    sockaddr_storage storage{};
    if (len > sizeof(storage)) return kNoPeer;
    std::memcpy(&storage, addr, len);
    std::string key = AddressKey(storage);
    if (key.empty()) return kNoPeer;
    auto it = m_byAddress.find(key);
    if (it != m_byAddress.end()) return it->second;
    // The lowest free slot, so ids depend only on the order peers appeared.
    for (size_t i = 0; i < m_slots.size(); ++i) {
        Slot& slot = m_slots[i];
        if (slot.used) continue;
        slot.used = true;
        slot.addr = storage;
        slot.len = static_cast<socklen_t>(len);
        slot.key = key;
        m_byAddress.emplace(std::move(key), static_cast<PeerId>(i));
        return static_cast<PeerId>(i);
    }
    return kNoPeer;
}

PeerId UdpTransport::AddPeer(const std::string& host, uint16_t port, std::string* error) {
    if (port == 0) {
        SetError(error, "port 0 is not a peer port");
        return kNoPeer;
    }
    sockaddr_storage addr{};
    socklen_t len = 0;
    if (host.empty() || !Resolve(host, port, AF_UNSPEC, false, addr, len, error)) {
        if (host.empty()) SetError(error, "empty peer address");
        return kNoPeer;
    }
    if (addr.ss_family == AF_INET && m_ipv6) {
        sockaddr_in6 mapped{};
        MapToV6(reinterpret_cast<const sockaddr_in&>(addr), mapped);
        std::memset(&addr, 0, sizeof(addr));
        std::memcpy(&addr, &mapped, sizeof(mapped));
        len = sizeof(mapped);
    } else if (addr.ss_family == AF_INET6 && !m_ipv6) {
        SetError(error, "IPv6 peer '" + host + "' on an IPv4 socket");
        return kNoPeer;
    }
    const PeerId id = Admit(&addr, len);
    if (id == kNoPeer) SetError(error, "peer table full");
    return id;
}

std::string UdpTransport::PeerAddress(PeerId peer) const {
    if (peer >= m_slots.size() || !m_slots[peer].used) return {};
    const Slot& slot = m_slots[peer];
    char text[INET6_ADDRSTRLEN] = {};
    if (slot.addr.ss_family == AF_INET) {
        const auto& a = reinterpret_cast<const sockaddr_in&>(slot.addr);
        ::inet_ntop(AF_INET, &a.sin_addr, text, sizeof(text));
        return std::string(text) + ":" + std::to_string(ntohs(a.sin_port));
    }
    const auto& a = reinterpret_cast<const sockaddr_in6&>(slot.addr);
    ::inet_ntop(AF_INET6, &a.sin6_addr, text, sizeof(text));
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "[" + std::string.
    std::string result(1, '[');
    result += text;
    result += "]:";
    result += std::to_string(ntohs(a.sin6_port));
    return result;
}

bool UdpTransport::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    (void)delivery;  // plain UDP has one kind of delivery
    if (peer >= m_slots.size() || !m_slots[peer].used || bytes.empty() || bytes.size() > MaxDatagram()) {
        ++m_stats.sendFailures;
        return false;
    }
    const Slot& slot = m_slots[peer];
    ssize_t sent;
    do {
        sent = ::sendto(m_fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&slot.addr), slot.len);
    } while (sent < 0 && errno == EINTR);
    if (sent < 0 || static_cast<size_t>(sent) != bytes.size()) {
        ++m_stats.sendFailures;
        return false;
    }
    const bool v4OnWire = slot.addr.ss_family == AF_INET || IsMappedV4(slot.addr);
    m_stats.datagramsSent += 1;
    m_stats.payloadBytesSent += bytes.size();
    m_stats.wireBytesSent += bytes.size() + (v4OnWire ? kIpv4Overhead : kIpv6Overhead);
    return true;
}

size_t UdpTransport::Poll(std::vector<Datagram>& out) {
    size_t count = 0;
    // Bounded: at most kMaxPollPerCall reads (plus the interrupted ones, which also count).
    for (size_t reads = 0; reads < kMaxPollPerCall; ++reads) {
        sockaddr_storage from{};
        socklen_t fromLen = sizeof(from);
        const ssize_t n =
            ::recvfrom(m_fd, m_buffer.data(), m_buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &fromLen);
        if (n < 0) {
            if (errno == EINTR) continue;
            // EAGAIN: drained. ECONNREFUSED and the like: an ICMP error from an earlier send,
            // which says nothing about the datagrams still queued, so keep reading.
            if (errno == EAGAIN || errno == EWOULDBLOCK) break;
            if (errno == ECONNREFUSED || errno == EHOSTUNREACH || errno == ENETUNREACH) continue;
            break;
        }
        if (n == 0 || static_cast<size_t>(n) > MaxDatagram()) {
            ++m_droppedMalformed;
            continue;
        }
        if (fromLen > sizeof(from)) continue;
        const PeerId peer = Admit(&from, fromLen);
        if (peer == kNoPeer) {
            ++m_stats.droppedUnknown;
            continue;
        }
        const auto size = static_cast<size_t>(n);
        out.push_back(Datagram{peer, std::vector<uint8_t>(m_buffer.begin(), m_buffer.begin() + n)});
        m_stats.datagramsReceived += 1;
        m_stats.payloadBytesReceived += size;
        ++count;
    }
    return count;
}

uint64_t UdpTransport::NowMicros() const {
    const auto us =
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
    return us < 0 ? 0 : static_cast<uint64_t>(us);
}

void UdpTransport::Disconnect(PeerId peer) {
    if (peer >= m_slots.size() || !m_slots[peer].used) return;
    m_byAddress.erase(m_slots[peer].key);
    m_slots[peer] = Slot{};
}

bool UdpTransport::WaitReadable(int timeoutMillis) const {
    pollfd p{};
    p.fd = m_fd;
    p.events = POLLIN;
    const int timeout = timeoutMillis < 0 ? 0 : (timeoutMillis > 60000 ? 60000 : timeoutMillis);
    int rc;
    do {
        rc = ::poll(&p, 1, timeout);
    } while (rc < 0 && errno == EINTR);
    return rc > 0 && (p.revents & POLLIN) != 0;
}

}  // namespace lockbox::net
