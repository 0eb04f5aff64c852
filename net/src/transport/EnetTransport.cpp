// EnetTransport: ENet host, peer table and the throttle configuration that never drops inputs.
#include "lockbox/net/EnetTransport.h"

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <utility>

#include <enet/enet.h>

#include "transport/SocketSetup.h"

namespace lockbox::net {

using transport_detail::kSocketBufferBytes;
using transport_detail::SetError;

struct EnetTransport::Slot {
    ENetPeer* peer = nullptr;  // null: the slot is free
    bool connected = false;
    std::vector<std::pair<Delivery, std::vector<uint8_t>>> pending;  // sent while connecting
};

namespace {

constexpr size_t kChannels = 2;

// ENet keeps global state (on Windows, Winsock); initialize it once per process and tear it
// down at exit, after every transport is gone.
bool EnsureEnet(std::string* error) {
    static std::once_flag once;
    static bool ok = false;
    std::call_once(once, [] {
        ok = enet_initialize() == 0;
        if (ok) std::atexit(enet_deinitialize);
    });
    if (!ok) SetError(error, "enet_initialize failed");
    return ok;
}

// A slot id rides in the peer's user data as id + 1, so null means "not ours".
void* SlotTag(PeerId id) { return reinterpret_cast<void*>(static_cast<uintptr_t>(id) + 1); }

PeerId SlotOf(const ENetPeer* peer) {
    const auto tag = reinterpret_cast<uintptr_t>(peer->data);
    return tag == 0 ? kNoPeer : static_cast<PeerId>(tag - 1);
}

ENetHost* CreateHost(const ENetAddress* address, size_t maxPeers, std::string* error) {
    if (maxPeers == 0 || maxPeers > EnetTransport::kMaxPeersLimit) {
        SetError(error, "maxPeers must be in 1..4095");
        return nullptr;
    }
    if (!EnsureEnet(error)) return nullptr;
    // 0, 0: no bandwidth limit, so ENet's bandwidth throttle never lowers the packet throttle.
    ENetHost* host = enet_host_create(address, maxPeers, kChannels, 0, 0);
    if (host == nullptr) {
        SetError(error, "enet_host_create failed (address in use or no socket)");
        return nullptr;
    }
    host->mtu = EnetTransport::kMtu;
    (void)enet_socket_set_option(host->socket, ENET_SOCKOPT_RCVBUF, kSocketBufferBytes);
    (void)enet_socket_set_option(host->socket, ENET_SOCKOPT_SNDBUF, kSocketBufferBytes);
    return host;
}

}  // namespace

std::unique_ptr<EnetTransport> EnetTransport::Listen(uint16_t port, size_t maxPeers, std::string* error,
                                                     const std::string& bindHost) {
    ENetAddress address{};
    if (!EnsureEnet(error)) return nullptr;
    if (enet_address_set_host_ip(&address, bindHost.c_str()) != 0) {
        SetError(error, "cannot parse IPv4 address '" + bindHost + "'");
        return nullptr;
    }
    address.port = port;
    ENetHost* host = CreateHost(&address, maxPeers, error);
    if (host == nullptr) return nullptr;
    return std::unique_ptr<EnetTransport>(new EnetTransport(host, maxPeers));
}

std::unique_ptr<EnetTransport> EnetTransport::Client(std::string* error, size_t maxPeers) {
    ENetHost* host = CreateHost(nullptr, maxPeers, error);
    if (host == nullptr) return nullptr;
    return std::unique_ptr<EnetTransport>(new EnetTransport(host, maxPeers));
}

EnetTransport::EnetTransport(ENetHost* host, size_t maxPeers) : m_host(host), m_slots(maxPeers) {}

EnetTransport::~EnetTransport() {
    // Tell every peer now (one unreliable disconnect each) rather than let them time out.
    for (Slot& slot : m_slots) {
        if (slot.peer == nullptr) continue;
        slot.peer->data = nullptr;
        enet_peer_disconnect_now(slot.peer, 0);
    }
    enet_host_destroy(m_host);
}

PeerId EnetTransport::FreeSlot() const noexcept {
    for (size_t i = 0; i < m_slots.size(); ++i)
        if (m_slots[i].peer == nullptr) return static_cast<PeerId>(i);
    return kNoPeer;
}

void EnetTransport::Bind(PeerId id, ENetPeer* peer) {
    m_slots[id] = Slot{};
    m_slots[id].peer = peer;
    peer->data = SlotTag(id);
}

void EnetTransport::Release(PeerId id) {
    if (m_slots[id].peer != nullptr) m_slots[id].peer->data = nullptr;
    m_slots[id] = Slot{};
}

void EnetTransport::OnConnected(PeerId id) {
    Slot& slot = m_slots[id];
    slot.connected = true;
    // Keep the unreliable throttle pinned at the scale on this end; the call also sends the
    // same parameters to the remote end, so its side of the connection never throttles either.
    // The throttle starts at the scale (enet_peer_reset), so pinning the steps is enough.
    enet_peer_throttle_configure(slot.peer, ENET_PEER_PACKET_THROTTLE_INTERVAL, ENET_PEER_PACKET_THROTTLE_SCALE, 0);
    for (auto& [delivery, bytes] : slot.pending) {
        if (!SendNow(slot.peer, bytes, delivery)) ++m_stats.sendFailures;
    }
    slot.pending.clear();
    enet_host_flush(m_host);
    m_connected.push_back(id);
}

PeerId EnetTransport::Connect(const std::string& host, uint16_t port, std::string* error) {
    ENetAddress address{};
    if (port == 0 || enet_address_set_host_ip(&address, host.c_str()) != 0) {
        SetError(error, "cannot parse IPv4 address '" + host + "' port " + std::to_string(port));
        return kNoPeer;
    }
    address.port = port;
    const PeerId id = FreeSlot();
    if (id == kNoPeer) {
        SetError(error, "peer table full");
        return kNoPeer;
    }
    ENetPeer* peer = enet_host_connect(m_host, &address, kChannels, 0);
    if (peer == nullptr) {
        SetError(error, "enet_host_connect failed (no free ENet peer)");
        return kNoPeer;
    }
    Bind(id, peer);
    enet_host_flush(m_host);
    return id;
}

uint16_t EnetTransport::LocalPort() const noexcept {
    ENetAddress address{};
    if (enet_socket_get_address(m_host->socket, &address) != 0) return 0;
    return address.port;
}

bool EnetTransport::IsConnected(PeerId peer) const noexcept {
    return peer < m_slots.size() && m_slots[peer].peer != nullptr && m_slots[peer].connected;
}

uint32_t EnetTransport::RoundTripMillis(PeerId peer) const noexcept {
    return IsConnected(peer) ? m_slots[peer].peer->roundTripTime : 0;
}

uint32_t EnetTransport::PacketThrottle(PeerId peer) const noexcept {
    return IsConnected(peer) ? m_slots[peer].peer->packetThrottle : 0;
}

std::vector<PeerId> EnetTransport::TakeConnected() { return std::exchange(m_connected, {}); }

std::vector<PeerId> EnetTransport::TakeDisconnected() { return std::exchange(m_disconnected, {}); }

bool EnetTransport::SendNow(ENetPeer* peer, std::span<const uint8_t> bytes, Delivery delivery) {
    const bool reliable = delivery == Delivery::e_reliable;
    ENetPacket* packet = enet_packet_create(bytes.data(), bytes.size(),
                                            reliable ? ENET_PACKET_FLAG_RELIABLE : ENET_PACKET_FLAG_UNSEQUENCED);
    if (packet == nullptr) return false;
    if (enet_peer_send(peer, reliable ? kReliableChannel : kUnreliableChannel, packet) != 0) {
        enet_packet_destroy(packet);  // on failure ENet did not take the packet
        return false;
    }
    return true;
}

bool EnetTransport::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    if (peer >= m_slots.size() || m_slots[peer].peer == nullptr || bytes.empty() || bytes.size() > MaxDatagram()) {
        ++m_stats.sendFailures;
        return false;
    }
    Slot& slot = m_slots[peer];
    if (!slot.connected) {
        if (slot.pending.size() >= kMaxPendingPerPeer) {
            ++m_stats.sendFailures;
            return false;
        }
        slot.pending.emplace_back(delivery, std::vector<uint8_t>(bytes.begin(), bytes.end()));
    } else {
        if (!SendNow(slot.peer, bytes, delivery)) {
            ++m_stats.sendFailures;
            return false;
        }
        // Out now rather than at the next Poll: an input waiting a tick is latency.
        enet_host_flush(m_host);
    }
    m_stats.datagramsSent += 1;
    m_stats.payloadBytesSent += bytes.size();
    m_stats.wireBytesSent += bytes.size() + kWireOverhead;
    return true;
}

size_t EnetTransport::Poll(std::vector<Datagram>& out) {
    size_t count = 0;
    ENetEvent event{};
    for (size_t handled = 0; handled < kMaxEventsPerPoll; ++handled) {
        if (enet_host_service(m_host, &event, 0) <= 0) break;
        const PeerId id = SlotOf(event.peer);
        switch (event.type) {
            case ENET_EVENT_TYPE_CONNECT:
                if (id != kNoPeer) {
                    OnConnected(id);  // a connection we started
                    break;
                }
                if (const PeerId free = FreeSlot(); free != kNoPeer) {
                    Bind(free, event.peer);
                    OnConnected(free);
                } else {
                    ++m_stats.droppedUnknown;
                    enet_peer_disconnect_now(event.peer, 0);
                }
                break;
            case ENET_EVENT_TYPE_RECEIVE: {
                ENetPacket* packet = event.packet;
                if (id == kNoPeer) {
                    ++m_stats.droppedUnknown;
                } else if (packet->dataLength == 0 || packet->dataLength > MaxDatagram()) {
                    ++m_droppedMalformed;
                } else {
                    out.push_back(Datagram{id, std::vector<uint8_t>(packet->data, packet->data + packet->dataLength)});
                    m_stats.datagramsReceived += 1;
                    m_stats.payloadBytesReceived += packet->dataLength;
                    ++count;
                }
                enet_packet_destroy(packet);
                break;
            }
            case ENET_EVENT_TYPE_DISCONNECT:
                if (id != kNoPeer) {
                    Release(id);
                    m_disconnected.push_back(id);
                }
                break;
            case ENET_EVENT_TYPE_NONE: break;
        }
    }
    return count;
}

uint64_t EnetTransport::NowMicros() const {
    const auto us =
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
    return us < 0 ? 0 : static_cast<uint64_t>(us);
}

void EnetTransport::Disconnect(PeerId peer) {
    if (peer >= m_slots.size() || m_slots[peer].peer == nullptr) return;
    ENetPeer* enetPeer = m_slots[peer].peer;
    Release(peer);
    enet_peer_disconnect(enetPeer, 0);
    enet_host_flush(m_host);
}

bool EnetTransport::WaitReadable(int timeoutMillis) const {
    const int timeout = timeoutMillis < 0 ? 0 : (timeoutMillis > 60000 ? 60000 : timeoutMillis);
    enet_uint32 condition = ENET_SOCKET_WAIT_RECEIVE;
    if (enet_socket_wait(m_host->socket, &condition, static_cast<enet_uint32>(timeout)) != 0) return false;
    return (condition & ENET_SOCKET_WAIT_RECEIVE) != 0;
}

}  // namespace lockbox::net
