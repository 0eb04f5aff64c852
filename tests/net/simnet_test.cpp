// SimNet: every impairment of the in-memory network, and determinism by seed.
#include "lockbox/net/SimNet.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

std::string SeedTrace(uint64_t seed) { return "SimNet seed=" + std::to_string(seed); }

// A payload that carries its index, so tests can see order, loss and duplicates.
std::vector<uint8_t> Numbered(uint32_t index, size_t size = 8) {
    std::vector<uint8_t> bytes(size < 4 ? 4 : size, 0xAB);
    std::memcpy(bytes.data(), &index, sizeof(index));
    return bytes;
}

uint32_t NumberOf(const Datagram& d) {
    uint32_t index = 0;
    std::memcpy(&index, d.bytes.data(), sizeof(index));
    return index;
}

// Jumps the clock to each next arrival until `until`, polling `receiver` and recording the
// arrival time of every datagram. Bounded by the number of datagrams in flight.
struct Arrival {
    uint64_t time;
    Datagram datagram;
};

std::vector<Arrival> DrainUntil(SimNet& net, SimEndpoint& receiver, uint64_t until) {
    std::vector<Arrival> arrivals;
    std::vector<Datagram> got;
    for (;;) {
        got.clear();
        receiver.Poll(got);
        for (Datagram& d : got) arrivals.push_back(Arrival{net.NowMicros(), std::move(d)});
        const uint64_t next = net.NextDueMicros();
        if (next == std::numeric_limits<uint64_t>::max() || next > until) break;
        // Due now but not ours: it waits in another endpoint's inbox, so we are done.
        if (next <= net.NowMicros()) break;
        net.Advance(next - net.NowMicros());
    }
    return arrivals;
}

TEST(SimNetTest, PerfectLinkDeliversInOrderAtExactLatency) {
    const uint64_t seed = 1;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.latencyMicros = 5000;
    net.SetAllLinks(p);
    for (uint32_t i = 0; i < 100; ++i) ASSERT_TRUE(a.Send(b.Index(), Numbered(i)));
    std::vector<Datagram> got;
    net.Advance(4999);
    EXPECT_EQ(b.Poll(got), 0u);
    net.Advance(1);
    ASSERT_EQ(b.Poll(got), 100u);
    for (uint32_t i = 0; i < 100; ++i) {
        EXPECT_EQ(got[i].peer, a.Index());
        EXPECT_EQ(NumberOf(got[i]), i);
        EXPECT_EQ(got[i].bytes.size(), 8u);
    }
    EXPECT_EQ(a.Stats().datagramsSent, 100u);
    EXPECT_EQ(a.Stats().wireBytesSent, 100u * (8 + SimNet::kWireOverhead));
    EXPECT_EQ(b.Stats().datagramsReceived, 100u);
    EXPECT_EQ(b.Stats().payloadBytesReceived, 800u);
    EXPECT_EQ(net.Link(a.Index(), b.Index()).delivered, 100u);
    EXPECT_EQ(net.Link(b.Index(), a.Index()).sent, 0u);
    EXPECT_EQ(a.NowMicros(), 5000u);
    EXPECT_EQ(net.InFlight(), 0u);
}

TEST(SimNetTest, InvalidSendsAreRefusedAndCounted) {
    SimNet net(2);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    const std::vector<uint8_t> ok(10, 1), empty, big(a.MaxDatagram() + 1, 1), max(a.MaxDatagram(), 1);
    EXPECT_FALSE(a.Send(a.Index(), ok));
    EXPECT_FALSE(a.Send(7, ok));
    EXPECT_FALSE(a.Send(kNoPeer, ok));
    EXPECT_FALSE(a.Send(b.Index(), empty));
    EXPECT_FALSE(a.Send(b.Index(), big));
    EXPECT_TRUE(a.Send(b.Index(), max));
    EXPECT_EQ(a.Stats().sendFailures, 5u);
    EXPECT_EQ(a.Stats().datagramsSent, 1u);
    EXPECT_THROW(net.Endpoint(9), std::out_of_range);
    EXPECT_THROW(net.SetLink(0, 0, LinkProfile{}), std::out_of_range);
    EXPECT_THROW(net.Blackout(0, 5, 0, 1), std::out_of_range);
}

TEST(SimNetTest, BernoulliLossWithinBinomialTolerance) {
    const uint64_t seed = 3;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.lossPpm = 100000;  // 10 %
    net.SetLink(0, 1, p);
    const uint32_t n = 100000;
    for (uint32_t i = 0; i < n; ++i) ASSERT_TRUE(a.Send(1, Numbered(i)));
    std::vector<Datagram> got;
    b.Poll(got);
    const LinkStats& s = net.Link(0, 1);
    // Mean 10,000, standard deviation sqrt(n p (1-p)) ~ 95: allow 5 deviations.
    EXPECT_NEAR(static_cast<double>(s.lost), 10000.0, 475.0);
    EXPECT_EQ(s.lost + s.delivered, n);
    EXPECT_EQ(got.size(), s.delivered);
}

TEST(SimNetTest, BurstLossComesInRuns) {
    const uint64_t seed = 4;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.burstEnterPpm = 10000;   // 1 % chance per datagram to enter a burst
    p.burstLeavePpm = 200000;  // mean burst 1e6 / 200000 = 5 datagrams
    p.burstLossPpm = 1000000;  // everything in a burst is lost
    net.SetLink(0, 1, p);
    const uint32_t n = 100000;
    for (uint32_t i = 0; i < n; ++i) ASSERT_TRUE(a.Send(1, Numbered(i)));
    std::vector<Datagram> got;
    b.Poll(got);
    std::vector<bool> arrived(n, false);
    for (const Datagram& d : got) arrived[NumberOf(d)] = true;
    uint64_t runs = 0, lostTotal = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (arrived[i]) continue;
        ++lostTotal;
        if (i == 0 || arrived[i - 1]) ++runs;
    }
    ASSERT_GT(runs, 500u);
    const double meanRun = static_cast<double>(lostTotal) / static_cast<double>(runs);
    EXPECT_GT(meanRun, 4.0);
    EXPECT_LT(meanRun, 6.0);
    EXPECT_EQ(lostTotal, net.Link(0, 1).lost);
}

TEST(SimNetTest, JitterStaysInBoundsAndReorders) {
    const uint64_t seed = 5;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.latencyMicros = 10000;
    p.jitterMicros = 5000;
    net.SetLink(0, 1, p);
    const uint32_t n = 1000;
    std::vector<Arrival> arrivals;
    for (uint32_t i = 0; i < n; ++i) {
        ASSERT_TRUE(a.Send(1, Numbered(i)));
        net.Advance(100);
        for (Arrival& r : DrainUntil(net, b, net.NowMicros())) arrivals.push_back(std::move(r));
    }
    for (Arrival& r : DrainUntil(net, b, std::numeric_limits<uint64_t>::max())) arrivals.push_back(std::move(r));
    ASSERT_EQ(arrivals.size(), n);
    uint64_t minDelay = std::numeric_limits<uint64_t>::max(), maxDelay = 0, inversions = 0;
    for (size_t k = 0; k < arrivals.size(); ++k) {
        const uint32_t i = NumberOf(arrivals[k].datagram);
        const uint64_t sentAt = uint64_t{i} * 100;
        // Arrivals are seen at the end of a 100 us step at worst, never before they are due.
        const uint64_t delay = arrivals[k].time - sentAt;
        minDelay = std::min(minDelay, delay);
        maxDelay = std::max(maxDelay, delay);
        if (k > 0 && i < NumberOf(arrivals[k - 1].datagram)) ++inversions;
    }
    EXPECT_GE(minDelay, 10000u);
    EXPECT_LE(maxDelay, 15000u + 100u);
    EXPECT_LT(minDelay, 10300u);  // the draws cover the range
    EXPECT_GT(maxDelay, 14700u);
    EXPECT_GT(inversions, 50u);
}

TEST(SimNetTest, DuplicationRate) {
    const uint64_t seed = 6;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.duplicatePpm = 50000;  // 5 %
    p.jitterMicros = 1000;
    net.SetLink(0, 1, p);
    const uint32_t n = 100000;
    for (uint32_t i = 0; i < n; ++i) ASSERT_TRUE(a.Send(1, Numbered(i)));
    net.Advance(1000);
    std::vector<Datagram> got;
    b.Poll(got);
    const LinkStats& s = net.Link(0, 1);
    // Mean 5,000, standard deviation ~69: allow 5 deviations.
    EXPECT_NEAR(static_cast<double>(s.duplicated), 5000.0, 345.0);
    EXPECT_EQ(got.size(), n + s.duplicated);
    std::vector<uint32_t> copies(n, 0);
    for (const Datagram& d : got) ++copies[NumberOf(d)];
    for (uint32_t i = 0; i < n; ++i) ASSERT_TRUE(copies[i] == 1 || copies[i] == 2) << i;
}

TEST(SimNetTest, ReorderHoldsDatagramsBack) {
    const uint64_t seed = 7;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.latencyMicros = 2000;
    p.reorderPpm = 100000;
    p.reorderDelayMicros = 30000;
    net.SetLink(0, 1, p);
    const uint32_t n = 2000;
    std::vector<Arrival> arrivals;
    for (uint32_t i = 0; i < n; ++i) {
        ASSERT_TRUE(a.Send(1, Numbered(i)));
        net.Advance(1000);
        for (Arrival& r : DrainUntil(net, b, net.NowMicros())) arrivals.push_back(std::move(r));
    }
    for (Arrival& r : DrainUntil(net, b, std::numeric_limits<uint64_t>::max())) arrivals.push_back(std::move(r));
    ASSERT_EQ(arrivals.size(), n);
    uint64_t held = 0;
    for (const Arrival& r : arrivals) {
        const uint64_t delay = r.time - uint64_t{NumberOf(r.datagram)} * 1000;
        EXPECT_TRUE(delay == 2000 || delay == 32000) << delay;
        if (delay == 32000) ++held;
    }
    EXPECT_EQ(held, net.Link(0, 1).reordered);
    EXPECT_NEAR(static_cast<double>(held), 200.0, 70.0);  // sd ~13
}

TEST(SimNetTest, BandwidthCapThroughputAndTailDrop) {
    const uint64_t seed = 8;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.latencyMicros = 1000;
    p.bandwidthBitsPerSecond = 1000000;  // 1 Mbit/s: a 1000-byte wire datagram takes 8 ms
    p.queueLimitBytes = 20000;
    net.SetLink(0, 1, p);
    const size_t payload = 1000 - SimNet::kWireOverhead;

    // An idle link: serialization plus latency, exactly.
    ASSERT_TRUE(a.Send(1, std::vector<uint8_t>(payload, 1)));
    auto first = DrainUntil(net, b, std::numeric_limits<uint64_t>::max());
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(first[0].time, 8000u + 1000u);

    // Offer 2 Mbit/s for 2 s: the link carries 1 Mbit/s, the queue overflows.
    net.Advance(100000);
    const uint64_t start = net.NowMicros();
    uint64_t wireInWindow = 0;
    std::vector<Datagram> got;
    for (uint32_t i = 0; i < 500; ++i) {
        ASSERT_TRUE(a.Send(1, std::vector<uint8_t>(payload, 2)));
        net.Advance(4000);
        got.clear();
        b.Poll(got);
        const uint64_t t = net.NowMicros() - start;
        if (t > 500000 && t <= 1500000) wireInWindow += got.size() * 1000;
    }
    // One second of a saturated 1 Mbit/s link: 125,000 bytes, give or take one datagram.
    EXPECT_NEAR(static_cast<double>(wireInWindow), 125000.0, 2000.0);
    const LinkStats& s = net.Link(0, 1);
    EXPECT_GT(s.queueDropped, 200u);
    DrainUntil(net, b, std::numeric_limits<uint64_t>::max());
    EXPECT_EQ(s.delivered + s.queueDropped, s.sent);
    EXPECT_EQ(s.wireBytes, 501u * 1000u);
}

TEST(SimNetTest, BlackoutWindowDropsOnlyInside) {
    const uint64_t seed = 9;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    net.Blackout(0, 1, 20000, 50000);
    std::vector<Datagram> toB, toA;
    for (uint32_t i = 0; i < 100; ++i) {
        ASSERT_TRUE(a.Send(1, Numbered(i)));
        ASSERT_TRUE(b.Send(0, Numbered(i)));
        net.Advance(1000);
        b.Poll(toB);
        a.Poll(toA);
    }
    EXPECT_EQ(toA.size(), 100u);  // the other direction is untouched
    ASSERT_EQ(toB.size(), 70u);
    for (const Datagram& d : toB) EXPECT_TRUE(NumberOf(d) < 20 || NumberOf(d) >= 50) << NumberOf(d);
    EXPECT_EQ(net.Link(0, 1).blackoutDropped, 30u);
}

TEST(SimNetTest, DownEndpointNeitherSendsNorReceives) {
    const uint64_t seed = 10;
    SCOPED_TRACE(SeedTrace(seed));
    SimNet net(seed);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.latencyMicros = 10000;
    net.SetAllLinks(p);
    std::vector<Datagram> got;

    ASSERT_TRUE(a.Send(1, Numbered(1)));  // in flight when b goes down
    net.Advance(5000);
    b.SetDown(true);
    EXPECT_TRUE(b.IsDown());
    EXPECT_TRUE(b.Send(0, Numbered(2)));  // accepted, silently lost
    net.Advance(10000);                   // datagram 1 arrives while b is down
    b.SetDown(false);
    EXPECT_EQ(b.Poll(got), 0u);
    ASSERT_TRUE(a.Send(1, Numbered(3)));
    net.Advance(10000);
    EXPECT_EQ(a.Poll(got), 0u);
    ASSERT_EQ(b.Poll(got), 1u);
    EXPECT_EQ(NumberOf(got[0]), 3u);
    EXPECT_EQ(net.Link(0, 1).downDropped, 1u);
    EXPECT_EQ(net.Link(1, 0).downDropped, 1u);

    // Going down loses what had arrived but was not polled.
    ASSERT_TRUE(a.Send(1, Numbered(4)));
    net.Advance(10000);
    b.SetDown(true);
    b.SetDown(false);
    EXPECT_EQ(b.Poll(got), 0u);
    EXPECT_EQ(net.Link(0, 1).downDropped, 2u);
}

// A long random run with every impairment on three endpoints, folded into one hash.
uint64_t RandomRunHash(uint64_t seed) {
    SimNet net(seed);
    for (int i = 0; i < 3; ++i) net.AddEndpoint();
    LinkProfile p;
    p.latencyMicros = 20000;
    p.jitterMicros = 15000;
    p.lossPpm = 50000;
    p.burstEnterPpm = 20000;
    p.burstLeavePpm = 300000;
    p.burstLossPpm = 800000;
    p.duplicatePpm = 30000;
    p.reorderPpm = 50000;
    p.reorderDelayMicros = 40000;
    p.bandwidthBitsPerSecond = 2000000;
    p.queueLimitBytes = 8000;
    net.SetAllLinks(p);
    net.Blackout(2, 0, 300000, 400000);
    uint64_t driver = 12345;  // the test's own call sequence is fixed, whatever the seed
    uint64_t hash = 1469598103934665603ull;
    auto fold = [&hash](uint64_t v) {
        for (int k = 0; k < 8; ++k) {
            hash ^= (v >> (8 * k)) & 0xFF;
            hash *= 1099511628211ull;
        }
    };
    std::vector<Datagram> got;
    for (uint32_t step = 0; step < 10000; ++step) {
        driver = driver * 6364136223846793005ull + 1442695040888963407ull;
        const auto from = static_cast<PeerId>((driver >> 33) % 3);
        const auto to = static_cast<PeerId>((from + 1 + ((driver >> 40) & 1)) % 3);
        const size_t size = 1 + ((driver >> 45) % 200);
        net.Endpoint(from).Send(to, Numbered(step, size));
        net.Advance(250);
        for (PeerId e = 0; e < 3; ++e) {
            got.clear();
            net.Endpoint(e).Poll(got);
            for (const Datagram& d : got) {
                fold(net.NowMicros());
                fold(uint64_t{e} << 32 | d.peer);
                fold(NumberOf(d));
                fold(d.bytes.size());
            }
        }
    }
    return hash;
}

TEST(SimNetTest, SameSeedSameDeliveriesOtherSeedOthers) {
    for (uint64_t seed : {11ull, 12ull}) {
        SCOPED_TRACE(SeedTrace(seed));
        const uint64_t first = RandomRunHash(seed);
        EXPECT_EQ(first, RandomRunHash(seed));
        EXPECT_NE(first, RandomRunHash(seed + 100));
    }
}

TEST(SimNetTest, LinksDrawIndependently) {
    // The draws of 0 -> 1 do not depend on traffic on other links or on extra endpoints.
    const uint64_t seed = 13;
    SCOPED_TRACE(SeedTrace(seed));
    auto lostPattern = [=](bool otherTraffic) {
        SimNet net(seed);
        for (int i = 0; i < (otherTraffic ? 4 : 2); ++i) net.AddEndpoint();
        LinkProfile p;
        p.lossPpm = 300000;
        net.SetAllLinks(p);
        std::vector<Datagram> got;
        std::vector<uint32_t> seen;
        for (uint32_t i = 0; i < 1000; ++i) {
            if (otherTraffic) net.Endpoint(2).Send(3, Numbered(i));
            net.Endpoint(0).Send(1, Numbered(i));
            got.clear();
            net.Endpoint(1).Poll(got);
            for (const Datagram& d : got) seen.push_back(NumberOf(d));
        }
        return seen;
    };
    EXPECT_EQ(lostPattern(false), lostPattern(true));
}

TEST(SimNetTest, ThroughputFigure) {
    // Prints the datagrams per second SimNet moves (a figure, not asserted: machines are noisy).
    SimNet net(14);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& b = net.AddEndpoint();
    LinkProfile p;
    p.latencyMicros = 30000;
    p.jitterMicros = 10000;
    p.lossPpm = 10000;
    net.SetAllLinks(p);
    const std::vector<uint8_t> payload(40, 7);
    std::vector<Datagram> got;
    got.reserve(64);
    const uint32_t n = 100000;
    const auto t0 = std::chrono::steady_clock::now();
    for (uint32_t i = 0; i < n; ++i) {
        a.Send(1, payload);
        if (i % 16 == 15) {
            net.Advance(1000);
            got.clear();
            b.Poll(got);
        }
    }
    const auto us =
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ figure ] SimNet: %u datagrams in %lld us = %lld datagrams/s\n", n, static_cast<long long>(us),
                static_cast<long long>(us > 0 ? uint64_t{n} * 1000000 / static_cast<uint64_t>(us) : 0));
    EXPECT_GT(b.Stats().datagramsReceived, 0u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
