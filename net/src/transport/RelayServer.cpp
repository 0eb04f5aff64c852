// RelayServer: slot binding by token and forwarding (RelayServer.h).
#include "lockbox/net/RelayServer.h"

#include <stdexcept>

namespace lockbox::net {

RelayServer::RelayServer(Transport& transport, RelayServerConfig config)
    : m_transport(transport), m_config(std::move(config)) {
    if (m_config.tokens.size() < 2 || m_config.tokens.size() > kRelayMaxSlots)
        throw std::invalid_argument("RelayServer: the slot count (tokens) must be in 2 .. 64 (kRelayMaxSlots)");
    m_slotPeer.assign(m_config.tokens.size(), kNoPeer);
}

PeerId RelayServer::SlotPeer(uint32_t slot) const noexcept {
    return slot < m_slotPeer.size() ? m_slotPeer[slot] : kNoPeer;
}

int RelayServer::SlotOf(PeerId peer) const noexcept {
    // A handful of slots: a linear scan in slot order.
    for (size_t s = 0; s < m_slotPeer.size(); ++s)
        if (m_slotPeer[s] == peer) return static_cast<int>(s);
    return -1;
}

void RelayServer::Poll() {
    m_inbox.clear();
    m_transport.Poll(m_inbox);
    for (const Datagram& d : m_inbox) Handle(d);
}

int RelayServer::Release(PeerId peer) noexcept {
    const int slot = SlotOf(peer);
    if (slot >= 0) m_slotPeer[static_cast<size_t>(slot)] = kNoPeer;
    return slot;
}

void RelayServer::Handle(const Datagram& d) {
    const std::optional<RelayFrame> f = ParseRelayFrame(d.bytes);
    if (!f || f->matchId != m_config.matchId || f->slot >= m_slotPeer.size()) {
        ++m_stats.refused;
        return;
    }
    if (f->kind == RelayKind::e_join) {
        if (f->token != m_config.tokens[f->slot]) {
            ++m_stats.refused;
            return;
        }
        const int held = SlotOf(d.peer);
        if (held >= 0 && held != f->slot) {
            // One address, one slot: a member cannot hold two seats.
            ++m_stats.refused;
            return;
        }
        if (m_slotPeer[f->slot] != d.peer) {
            if (m_slotPeer[f->slot] != kNoPeer) ++m_stats.rebinds;
            m_slotPeer[f->slot] = d.peer;
        }
        ++m_stats.joins;
        // Answer every join: the member repeats it until a welcome gets through.
        WriteRelayFrame(m_out, RelayKind::e_welcome, m_config.matchId, f->slot);
        if (!m_transport.Send(d.peer, m_out, Delivery::e_reliable)) ++m_stats.sendFailures;
        return;
    }
    if (f->kind != RelayKind::e_toSlot) {
        ++m_stats.refused;  // welcome and from-slot only travel relay -> member
        return;
    }
    const int from = SlotOf(d.peer);
    const PeerId to = m_slotPeer[f->slot];
    if (from < 0 || to == kNoPeer || static_cast<int>(f->slot) == from) {
        ++m_stats.refused;
        return;
    }
    WriteRelayFrame(m_out, RelayKind::e_fromSlot, m_config.matchId, static_cast<uint8_t>(from), 0, f->payload);
    if (!m_transport.Send(to, m_out)) {
        ++m_stats.sendFailures;
        return;
    }
    ++m_stats.forwarded;
    m_stats.forwardedBytes += f->payload.size();
}

}  // namespace lockbox::net
