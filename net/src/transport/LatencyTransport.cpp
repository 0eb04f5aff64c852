// LatencyTransport: seeded impairment of received datagrams (see LatencyTransport.h).
#include "lockbox/net/LatencyTransport.h"

#include <iterator>
#include <limits>

#include "transport/SaturatingAdd.h"

namespace lockbox::net {

using transport_detail::SatAdd;

namespace {

constexpr uint64_t kPermille = 1000;

}  // namespace

LatencyTransport::LatencyTransport(Transport& inner, LatencyProfile profile, uint64_t seed)
    : m_inner(inner), m_profile(profile), m_seed(seed), m_state(seed) {}

// splitmix64: one word of state, every step a bijection, all arithmetic unsigned.
uint64_t LatencyTransport::Draw() noexcept {
    m_state += 0x9E3779B97F4A7C15ull;
    uint64_t z = m_state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// True with probability permille / 1000 (the modulo bias, 2^64 mod 1000 in 2^64, is nil in
// practice). A rate of 0 or >= 1000 draws nothing, so such profiles keep the stream unused.
bool LatencyTransport::Chance(uint32_t permille) noexcept {
    if (permille == 0) return false;
    if (permille >= kPermille) return true;
    return Draw() % kPermille < permille;
}

uint64_t LatencyTransport::Jitter() noexcept {
    return m_profile.jitterMicros == 0 ? 0 : Draw() % (uint64_t{m_profile.jitterMicros} + 1);
}

bool LatencyTransport::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    return m_inner.Send(peer, bytes, delivery);
}

size_t LatencyTransport::Poll(std::vector<Datagram>& out) {
    m_inbox.clear();
    m_inner.Poll(m_inbox);
    const uint64_t now = m_inner.NowMicros();
    for (Datagram& d : m_inbox) {
        ++m_impairments.received;
        if (Chance(m_profile.lossPermille)) {
            ++m_impairments.lost;
            continue;
        }
        uint64_t due = SatAdd(now, SatAdd(m_profile.latencyMicros, Jitter()));
        if (Chance(m_profile.reorderPermille)) {
            ++m_impairments.reordered;
            due = SatAdd(due, m_profile.reorderDelayMicros);
        }
        if (Chance(m_profile.duplicatePermille)) {
            ++m_impairments.duplicated;
            const uint64_t copyDue = SatAdd(now, SatAdd(m_profile.latencyMicros, Jitter()));
            m_held.emplace(std::make_pair(copyDue, m_arrival++), d);
        }
        m_held.emplace(std::make_pair(due, m_arrival++), std::move(d));
    }
    size_t handed = 0;
    while (!m_held.empty() && m_held.begin()->first.first <= now) {
        auto node = m_held.extract(m_held.begin());
        m_deliveredBytes += node.mapped().bytes.size();
        out.push_back(std::move(node.mapped()));
        ++handed;
    }
    m_impairments.delivered += handed;
    return handed;
}

const TransportStats& LatencyTransport::Stats() const noexcept {
    m_stats = m_inner.Stats();
    m_stats.datagramsReceived = m_impairments.delivered;
    m_stats.payloadBytesReceived = m_deliveredBytes;
    return m_stats;
}

void LatencyTransport::Disconnect(PeerId peer) {
    for (auto it = m_held.begin(); it != m_held.end();) {
        if (it->second.peer != peer) {
            ++it;
            continue;
        }
        it = m_held.erase(it);
        ++m_impairments.forgotten;
    }
    m_inner.Disconnect(peer);
}

uint64_t LatencyTransport::NextDueMicros() const noexcept {
    return m_held.empty() ? std::numeric_limits<uint64_t>::max() : m_held.begin()->first.first;
}

}  // namespace lockbox::net
