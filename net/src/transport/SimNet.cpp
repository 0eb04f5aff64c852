// SimNet: the in-memory, seeded, virtual-clock network (see SimNet.h for the datagram path).
#include "lockbox/net/SimNet.h"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace lockbox::net {
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

uint64_t SatAdd(uint64_t a, uint64_t b) {
    return a > std::numeric_limits<uint64_t>::max() - b ? std::numeric_limits<uint64_t>::max() : a + b;
}

// xoshiro256**: small state, good statistics, and all arithmetic is unsigned (wraps by design).
class Rng {
public:
    explicit Rng(uint64_t seed = 0) {
        for (uint64_t& word : s_) word = SplitMix(seed);
    }
    uint64_t Next() {
        const uint64_t result = Rotl(s_[1] * 5, 7) * 9;
        const uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = Rotl(s_[3], 45);
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
    uint64_t s_[4];
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
    bool operator()(const Packet& a, const Packet& b) const { return a.due != b.due ? a.due > b.due : a.seq > b.seq; }
};

}  // namespace

struct SimNet::Impl {
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
        const PeerId from = sender.index_;
        if (to >= endpoints.size() || to == from || bytes.empty() || bytes.size() > sender.MaxDatagram()) {
            ++sender.stats_.sendFailures;
            return false;
        }
        const uint64_t wire = bytes.size() + kWireOverhead;
        sender.stats_.datagramsSent += 1;
        sender.stats_.payloadBytesSent += bytes.size();
        sender.stats_.wireBytesSent += wire;
        LinkState& link = LinkFor(from, to);
        link.stats.sent += 1;
        link.stats.wireBytes += wire;
        if (sender.down_) {
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
        const PeerId to = receiver.index_;
        if (receiver.down_) {
            DropDue(to);
            return 0;
        }
        auto& heap = inboxes[to];
        size_t count = 0;
        while (!heap.empty() && heap.front().due <= now) {
            std::pop_heap(heap.begin(), heap.end(), Later{});
            Packet& item = heap.back();
            ++item.link->stats.delivered;
            receiver.stats_.datagramsReceived += 1;
            receiver.stats_.payloadBytesReceived += item.bytes.size();
            out.push_back(Datagram{item.from, std::move(item.bytes)});
            heap.pop_back();
            --inFlight;
            ++count;
        }
        return count;
    }
};

SimNet::SimNet(uint64_t seed) : impl_(std::make_unique<Impl>(seed)) {}
SimNet::~SimNet() = default;

SimEndpoint& SimNet::AddEndpoint() {
    const auto index = static_cast<PeerId>(impl_->endpoints.size());
    if (index == kNoPeer) throw std::length_error("SimNet: too many endpoints");
    impl_->endpoints.push_back(std::unique_ptr<SimEndpoint>(new SimEndpoint(*impl_, index)));
    impl_->inboxes.emplace_back();
    return *impl_->endpoints.back();
}

SimEndpoint& SimNet::Endpoint(PeerId index) { return *impl_->endpoints.at(index); }

size_t SimNet::EndpointCount() const noexcept { return impl_->endpoints.size(); }

void SimNet::SetLink(PeerId from, PeerId to, const LinkProfile& profile) {
    impl_->CheckPair(from, to);
    impl_->LinkFor(from, to).profile = profile;
}

void SimNet::SetAllLinks(const LinkProfile& profile) {
    impl_->defaultProfile = profile;
    for (auto& entry : impl_->links) entry.second.profile = profile;
}

void SimNet::Blackout(PeerId from, PeerId to, uint64_t startMicros, uint64_t endMicros) {
    impl_->CheckPair(from, to);
    if (endMicros > startMicros) impl_->LinkFor(from, to).blackouts.push_back(Window{startMicros, endMicros});
}

uint64_t SimNet::NowMicros() const noexcept { return impl_->now; }

void SimNet::Advance(uint64_t micros) {
    impl_->now = SatAdd(impl_->now, micros);
    for (const auto& endpoint : impl_->endpoints)
        if (endpoint->down_) impl_->DropDue(endpoint->index_);
}

uint64_t SimNet::NextDueMicros() const noexcept {
    uint64_t next = std::numeric_limits<uint64_t>::max();
    for (const auto& heap : impl_->inboxes)
        if (!heap.empty()) next = std::min(next, heap.front().due);
    return next;
}

size_t SimNet::InFlight() const noexcept { return impl_->inFlight; }

const LinkStats& SimNet::Link(PeerId from, PeerId to) const {
    static const LinkStats kNone{};
    auto it = impl_->links.find(std::make_pair(from, to));
    return it == impl_->links.end() ? kNone : it->second.stats;
}

uint64_t SimNet::Seed() const noexcept { return impl_->seed; }

bool SimEndpoint::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    (void)delivery;  // SimNet has no reliable channel: sessions resend what matters
    return net_->Send(*this, peer, bytes);
}

size_t SimEndpoint::Poll(std::vector<Datagram>& out) { return net_->Poll(*this, out); }

uint64_t SimEndpoint::NowMicros() const { return net_->now; }

void SimEndpoint::SetDown(bool down) noexcept {
    down_ = down;
    if (down) net_->DropDue(index_);
}

}  // namespace lockbox::net
