// SimNet: the in-memory, seeded, virtual-clock network (see SimNet.h for the datagram path).
#include "lockbox/net/SimNet.h"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "transport/SaturatingAdd.h"

namespace lockbox::net {

using transport_detail::SatAdd;

namespace {

constexpr uint64_t kPpmScale = 1000000;
constexpr uint64_t kMicrosPerSecond = 1000000;
constexpr uint64_t kMaxBandwidth = 1000000000000ull;  // 1 Tbit/s keeps every product in range

uint64_t SplitMix(uint64_t& state) {
    state += 0x9E3779B97F4A7C15ull;
    uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

}  // namespace

struct SimNet::Impl {
    // The types an Impl holds are nested in it rather than file-local: a class with external
    // linkage whose fields have internal-linkage types draws GCC's -Wsubobject-linkage when a
    // unity build includes this file.

    // xoshiro256**: small state, good statistics, and all arithmetic is unsigned (wraps by design).
    class Rng {
    public:
        explicit Rng(uint64_t seed = 0) {
            for (uint64_t& word : m_s) word = SplitMix(seed);
        }
        uint64_t Next() {
            const uint64_t result = Rotl(m_s[1] * 5, 7) * 9;
            const uint64_t t = m_s[1] << 17;
            m_s[2] ^= m_s[0];
            m_s[3] ^= m_s[1];
            m_s[1] ^= m_s[2];
            m_s[0] ^= m_s[3];
            m_s[2] ^= t;
            m_s[3] = Rotl(m_s[3], 45);
            return result;
        }
        // True with probability ppm / 1e6. The modulo bias (2^64 mod 1e6 out of 2^64) is negligible.
        bool Chance(uint32_t ppm) {
            if (ppm == 0) return false;
            if (ppm >= kPpmScale) return true;
            return Next() % kPpmScale < ppm;
        }
        // Uniform in [0, max].
        uint64_t UpTo(uint32_t max) { return max == 0 ? 0 : Next() % (uint64_t{max} + 1); }

    private:
        static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
        uint64_t m_s[4];
    };

    struct Window {
        uint64_t start, end;
    };

    struct LinkState {
        LinkProfile profile;
        Rng rng;
        LinkStats stats;
        std::vector<Window> blackouts;
        bool burstBad = false;
        // The transmitter is busy until busyUntil + busyFrac / bandwidth microseconds; keeping the
        // fraction exactly means a long run of datagrams has no rounding drift.
        uint64_t busyUntil = 0;
        uint64_t busyFrac = 0;
    };

    struct Packet {
        uint64_t due;
        uint64_t seq;
        PeerId from;
        LinkState* link;  // std::map nodes never move; saves a lookup per delivery
        std::vector<uint8_t> bytes;
    };

    // Heap order: the earliest (due, seq) on top. seq is unique per net, so the order is total.
    struct Later {
        bool operator()(const Packet& a, const Packet& b) const {
            return a.due != b.due ? a.due > b.due : a.seq > b.seq;
        }
    };

    uint64_t seed;
    uint64_t now = 0;
    uint64_t nextSeq = 0;
    size_t inFlight = 0;
    std::vector<std::unique_ptr<SimEndpoint>> endpoints;
    std::vector<std::vector<Packet>> inboxes;  // one heap per receiving endpoint
    std::map<std::pair<PeerId, PeerId>, LinkState> links;
    LinkProfile defaultProfile;

    explicit Impl(uint64_t s) : seed(s) {}

    void CheckPair(PeerId from, PeerId to) const {
        if (from >= endpoints.size() || to >= endpoints.size() || from == to)
            throw std::out_of_range("SimNet: no such link");
    }

    LinkState& LinkFor(PeerId from, PeerId to) {
        const auto key = std::make_pair(from, to);
        auto it = links.find(key);
        if (it != links.end()) return it->second;
        // The link's generator depends only on (seed, from, to), never on creation order.
        uint64_t mix = seed;
        uint64_t h = SplitMix(mix);
        mix = h ^ (uint64_t{from} << 32 | to);
        h = SplitMix(mix);
        LinkState link;
        link.profile = defaultProfile;
        link.rng = Rng(h);
        return links.emplace(key, std::move(link)).first->second;
    }

    void Push(LinkState& link, PeerId to, PeerId from, uint64_t due, std::vector<uint8_t> bytes) {
        auto& heap = inboxes[to];
        heap.push_back(Packet{due, nextSeq++, from, &link, std::move(bytes)});
        std::push_heap(heap.begin(), heap.end(), Later{});
        ++inFlight;
    }

    // Drops what is due by now for a receiver that is down: it arrived at an unplugged machine.
    void DropDue(PeerId to) {
        auto& heap = inboxes[to];
        while (!heap.empty() && heap.front().due <= now) {
            std::pop_heap(heap.begin(), heap.end(), Later{});
            ++heap.back().link->stats.downDropped;
            heap.pop_back();
            --inFlight;
        }
    }

    // Puts the datagram through the bandwidth queue; returns false when it is tail-dropped,
    // else sets `leftAt` to the time its last bit left the link.
    static bool Enqueue(LinkState& link, uint64_t now, uint64_t wireBytes, uint64_t& leftAt) {
        const uint64_t bps = std::min(link.profile.bandwidthBitsPerSecond, kMaxBandwidth);
        if (bps == 0) {
            leftAt = now;
            return true;
        }
        if (link.busyUntil < now || (link.busyUntil == now && link.busyFrac == 0)) {
            link.busyUntil = now;
            link.busyFrac = 0;
        } else {
            // busyUntil - now is at most (queue limit + one datagram) / bps seconds, so the
            // product stays below ~(2^32 + 1228) * 8e6 + bps, far from overflow.
            const uint64_t backlogUnits = (link.busyUntil - now) * bps + link.busyFrac;
            const uint64_t backlogBits = (backlogUnits + kMicrosPerSecond - 1) / kMicrosPerSecond;
            const uint64_t backlogBytes = (backlogBits + 7) / 8;
            if (backlogBytes + wireBytes > link.profile.queueLimitBytes) return false;
        }
        link.busyFrac += wireBytes * 8 * kMicrosPerSecond;  // in units of 1/bps microseconds
        link.busyUntil = SatAdd(link.busyUntil, link.busyFrac / bps);
        link.busyFrac %= bps;
        leftAt = link.busyFrac == 0 ? link.busyUntil : SatAdd(link.busyUntil, 1);
        return true;
    }

    bool Send(SimEndpoint& sender, PeerId to, std::span<const uint8_t> bytes) {
        const PeerId from = sender.m_index;
        if (to >= endpoints.size() || to == from || bytes.empty() || bytes.size() > sender.MaxDatagram()) {
            ++sender.m_stats.sendFailures;
            return false;
        }
        const uint64_t wire = bytes.size() + kWireOverhead;
        sender.m_stats.datagramsSent += 1;
        sender.m_stats.payloadBytesSent += bytes.size();
        sender.m_stats.wireBytesSent += wire;
        LinkState& link = LinkFor(from, to);
        link.stats.sent += 1;
        link.stats.wireBytes += wire;
        if (sender.m_down) {
            ++link.stats.downDropped;
            return true;
        }
        for (const Window& w : link.blackouts) {
            if (now >= w.start && now < w.end) {
                ++link.stats.blackoutDropped;
                return true;
            }
        }
        uint64_t leftAt = now;
        if (!Enqueue(link, now, wire, leftAt)) {
            ++link.stats.queueDropped;
            return true;
        }
        const LinkProfile& p = link.profile;
        bool lost = link.rng.Chance(p.lossPpm);
        if (p.burstEnterPpm != 0 || p.burstLeavePpm != 0) {
            // The state moves first, so a datagram can be the first one lost in a burst.
            if (link.burstBad ? link.rng.Chance(p.burstLeavePpm) : link.rng.Chance(p.burstEnterPpm))
                link.burstBad = !link.burstBad;
            if (link.burstBad && link.rng.Chance(p.burstLossPpm)) lost = true;
        }
        if (lost) {
            ++link.stats.lost;
            return true;
        }
        const uint64_t base = SatAdd(leftAt, p.latencyMicros);
        uint64_t due = SatAdd(base, link.rng.UpTo(p.jitterMicros));
        if (link.rng.Chance(p.reorderPpm)) {
            due = SatAdd(due, p.reorderDelayMicros);
            ++link.stats.reordered;
        }
        if (link.rng.Chance(p.duplicatePpm)) {
            ++link.stats.duplicated;
            const uint64_t copyDue = SatAdd(base, link.rng.UpTo(p.jitterMicros));
            Push(link, to, from, due, std::vector<uint8_t>(bytes.begin(), bytes.end()));
            Push(link, to, from, copyDue, std::vector<uint8_t>(bytes.begin(), bytes.end()));
        } else {
            Push(link, to, from, due, std::vector<uint8_t>(bytes.begin(), bytes.end()));
        }
        return true;
    }

    size_t Poll(SimEndpoint& receiver, std::vector<Datagram>& out) {
        const PeerId to = receiver.m_index;
        if (receiver.m_down) {
            DropDue(to);
            return 0;
        }
        auto& heap = inboxes[to];
        size_t count = 0;
        while (!heap.empty() && heap.front().due <= now) {
            std::pop_heap(heap.begin(), heap.end(), Later{});
            Packet& item = heap.back();
            ++item.link->stats.delivered;
            receiver.m_stats.datagramsReceived += 1;
            receiver.m_stats.payloadBytesReceived += item.bytes.size();
            out.push_back(Datagram{item.from, std::move(item.bytes)});
            heap.pop_back();
            --inFlight;
            ++count;
        }
        return count;
    }
};

SimNet::SimNet(uint64_t seed) : m_impl(std::make_unique<Impl>(seed)) {}
SimNet::~SimNet() = default;

SimEndpoint& SimNet::AddEndpoint() {
    const auto index = static_cast<PeerId>(m_impl->endpoints.size());
    if (index == kNoPeer) throw std::length_error("SimNet: too many endpoints");
    m_impl->endpoints.push_back(std::unique_ptr<SimEndpoint>(new SimEndpoint(*m_impl, index)));
    m_impl->inboxes.emplace_back();
    return *m_impl->endpoints.back();
}

SimEndpoint& SimNet::Endpoint(PeerId index) { return *m_impl->endpoints.at(index); }

size_t SimNet::EndpointCount() const noexcept { return m_impl->endpoints.size(); }

void SimNet::SetLink(PeerId from, PeerId to, const LinkProfile& profile) {
    m_impl->CheckPair(from, to);
    m_impl->LinkFor(from, to).profile = profile;
}

void SimNet::SetAllLinks(const LinkProfile& profile) {
    m_impl->defaultProfile = profile;
    for (auto& entry : m_impl->links) entry.second.profile = profile;
}

void SimNet::Blackout(PeerId from, PeerId to, uint64_t startMicros, uint64_t endMicros) {
    m_impl->CheckPair(from, to);
    if (endMicros > startMicros) m_impl->LinkFor(from, to).blackouts.push_back(Impl::Window{startMicros, endMicros});
}

uint64_t SimNet::NowMicros() const noexcept { return m_impl->now; }

void SimNet::Advance(uint64_t micros) {
    m_impl->now = SatAdd(m_impl->now, micros);
    for (const auto& endpoint : m_impl->endpoints)
        if (endpoint->m_down) m_impl->DropDue(endpoint->m_index);
}

uint64_t SimNet::NextDueMicros() const noexcept {
    uint64_t next = std::numeric_limits<uint64_t>::max();
    for (const auto& heap : m_impl->inboxes)
        if (!heap.empty()) next = std::min(next, heap.front().due);
    return next;
}

size_t SimNet::InFlight() const noexcept { return m_impl->inFlight; }

const LinkStats& SimNet::Link(PeerId from, PeerId to) const {
    static const LinkStats kNone{};
    auto it = m_impl->links.find(std::make_pair(from, to));
    return it == m_impl->links.end() ? kNone : it->second.stats;
}

uint64_t SimNet::Seed() const noexcept { return m_impl->seed; }

bool SimEndpoint::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    (void)delivery;  // SimNet has no reliable channel: sessions resend what matters
    return m_net->Send(*this, peer, bytes);
}

size_t SimEndpoint::Poll(std::vector<Datagram>& out) { return m_net->Poll(*this, out); }

uint64_t SimEndpoint::NowMicros() const { return m_net->now; }

void SimEndpoint::SetDown(bool down) noexcept {
    m_down = down;
    if (down) m_net->DropDue(m_index);
}

}  // namespace lockbox::net
