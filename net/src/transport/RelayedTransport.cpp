// RelayedTransport: slot-addressed datagrams through a RelayServer (RelayedTransport.h).
#include "lockbox/net/RelayedTransport.h"

#include <stdexcept>

namespace lockbox::net {

RelayedTransport::RelayedTransport(Transport& inner, RelayedTransportConfig config) : m_inner(inner), m_config(config) {
    if (m_config.slots < 2 || m_config.slots > kRelayMaxSlots)
        throw std::invalid_argument("RelayedTransport: slots must be in 2 .. 64 (kRelayMaxSlots)");
    if (m_config.slot >= m_config.slots) throw std::invalid_argument("RelayedTransport: slot must be < slots");
    if (m_config.relay == kNoPeer) throw std::invalid_argument("RelayedTransport: no relay peer");
    if (m_config.joinRetryMicros == 0) throw std::invalid_argument("RelayedTransport: joinRetryMicros must be >= 1");
    MaybeJoin();
}

void RelayedTransport::MaybeJoin() {
    if (m_joined) return;
    const uint64_t now = m_inner.NowMicros();
    if (m_joinSent && now - m_lastJoin < m_config.joinRetryMicros) return;
    WriteRelayFrame(m_out, RelayKind::e_join, m_config.matchId, static_cast<uint8_t>(m_config.slot), m_config.token);
    m_inner.Send(m_config.relay, m_out, Delivery::e_reliable);
    m_joinSent = true;
    m_lastJoin = now;
}

bool RelayedTransport::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    MaybeJoin();
    if (peer >= m_config.slots || peer == m_config.slot || bytes.empty() || bytes.size() > MaxDatagram()) {
        ++m_stats.sendFailures;
        return false;
    }
    WriteRelayFrame(m_out, RelayKind::e_toSlot, m_config.matchId, static_cast<uint8_t>(peer), 0, bytes);
    if (!m_inner.Send(m_config.relay, m_out, delivery)) {
        ++m_stats.sendFailures;
        return false;
    }
    ++m_stats.datagramsSent;
    m_stats.payloadBytesSent += bytes.size();
    m_stats.wireBytesSent += m_out.size();
    return true;
}

size_t RelayedTransport::Poll(std::vector<Datagram>& out) {
    m_inbox.clear();
    m_inner.Poll(m_inbox);
    size_t added = 0;
    for (Datagram& d : m_inbox) {
        const std::optional<RelayFrame> f =
            d.peer == m_config.relay ? ParseRelayFrame(d.bytes) : std::optional<RelayFrame>{};
        if (!f || f->matchId != m_config.matchId) {
            ++m_stats.droppedUnknown;
            continue;
        }
        if (f->kind == RelayKind::e_welcome && f->slot == m_config.slot) {
            m_joined = true;
            continue;
        }
        if (f->kind != RelayKind::e_fromSlot || f->slot >= m_config.slots || f->slot == m_config.slot) {
            ++m_stats.droppedUnknown;
            continue;
        }
        Datagram& o = out.emplace_back();
        o.peer = f->slot;
        o.bytes.assign(f->payload.begin(), f->payload.end());
        ++m_stats.datagramsReceived;
        m_stats.payloadBytesReceived += o.bytes.size();
        ++added;
    }
    MaybeJoin();
    return added;
}

}  // namespace lockbox::net
