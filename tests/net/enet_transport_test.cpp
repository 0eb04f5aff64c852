// EnetTransport on 127.0.0.1: connections, both channels, disconnects, an unthrottled burst.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/EnetTransport.h"
#include "lockbox/net/UdpTransport.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

using Clock = std::chrono::steady_clock;
constexpr uint32_t kThrottleScale = 32;  // ENET_PEER_PACKET_THROTTLE_SCALE

std::vector<uint8_t> Bytes(const std::string& text) { return std::vector<uint8_t>(text.begin(), text.end()); }
std::string Text(const Datagram& d) { return std::string(d.bytes.begin(), d.bytes.end()); }

// Polls every transport until `done` holds or `seconds` pass; received datagrams go to the
// matching inbox. Returns whether `done` held. Every iteration waits at most 1 ms.
bool Pump(std::vector<EnetTransport*> hosts, std::vector<std::vector<Datagram>>& inboxes,
          const std::function<bool()>& done, int seconds = 3) {
    inboxes.resize(hosts.size());
    const auto deadline = Clock::now() + std::chrono::seconds(seconds);
    while (Clock::now() < deadline) {
        size_t got = 0;
        for (size_t i = 0; i < hosts.size(); ++i) got += hosts[i]->Poll(inboxes[i]);
        if (done()) return true;
        if (got == 0) hosts[0]->WaitReadable(1);
    }
    return done();
}

struct Match {
    std::unique_ptr<EnetTransport> server, c1, c2;
    PeerId c1ToServer = kNoPeer, c2ToServer = kNoPeer;
    std::vector<PeerId> serverPeers;  // in connect order
};

void Connect(Match& m, int clients) {
    std::string error;
    m.server = EnetTransport::Listen(0, 8, &error);
    ASSERT_NE(m.server, nullptr) << error;
    const uint16_t port = m.server->LocalPort();
    ASSERT_NE(port, 0);
    m.c1 = EnetTransport::Client(&error);
    ASSERT_NE(m.c1, nullptr) << error;
    m.c1ToServer = m.c1->Connect("127.0.0.1", port, &error);
    ASSERT_NE(m.c1ToServer, kNoPeer) << error;
    if (clients > 1) {
        m.c2 = EnetTransport::Client(&error);
        ASSERT_NE(m.c2, nullptr) << error;
        m.c2ToServer = m.c2->Connect("127.0.0.1", port, &error);
        ASSERT_NE(m.c2ToServer, kNoPeer) << error;
    }
    std::vector<EnetTransport*> hosts{m.server.get(), m.c1.get()};
    if (m.c2) hosts.push_back(m.c2.get());
    std::vector<std::vector<Datagram>> inboxes;
    ASSERT_TRUE(Pump(hosts, inboxes, [&] {
        for (PeerId p : m.server->TakeConnected()) m.serverPeers.push_back(p);
        return m.serverPeers.size() == static_cast<size_t>(clients) && m.c1->IsConnected(m.c1ToServer) &&
               (!m.c2 || m.c2->IsConnected(m.c2ToServer));
    }));
    for (const auto& inbox : inboxes) ASSERT_TRUE(inbox.empty());
}

TEST(EnetTransportTest, ServerAndTwoClientsExchangeBothChannels) {
    std::string error;
    auto server = EnetTransport::Listen(0, 8, &error);
    ASSERT_NE(server, nullptr) << error;
    auto c1 = EnetTransport::Client(&error);
    auto c2 = EnetTransport::Client(&error);
    ASSERT_TRUE(c1 && c2) << error;
    const PeerId s1 = c1->Connect("127.0.0.1", server->LocalPort(), &error);
    ASSERT_NE(s1, kNoPeer) << error;
    // Sent while still connecting: waits, then leaves in order once connected.
    ASSERT_TRUE(c1->Send(s1, Bytes("early-reliable"), Delivery::e_reliable));
    ASSERT_TRUE(c1->Send(s1, Bytes("early-unreliable")));
    const PeerId s2 = c2->Connect("127.0.0.1", server->LocalPort(), &error);
    ASSERT_NE(s2, kNoPeer) << error;

    std::vector<std::vector<Datagram>> in;
    std::vector<PeerId> joined;
    ASSERT_TRUE(Pump({server.get(), c1.get(), c2.get()}, in, [&] {
        for (PeerId p : server->TakeConnected()) joined.push_back(p);
        return joined.size() == 2 && c2->IsConnected(s2) && in[0].size() >= 2;
    }));
    EXPECT_EQ(c1->TakeConnected(), std::vector<PeerId>{s1});
    ASSERT_EQ(in[0].size(), 2u);
    EXPECT_EQ(Text(in[0][0]), "early-reliable");
    EXPECT_EQ(Text(in[0][1]), "early-unreliable");
    const PeerId fromC1 = in[0][0].peer;
    EXPECT_NE(std::find(joined.begin(), joined.end(), fromC1), joined.end());
    const PeerId fromC2 = joined[0] == fromC1 ? joined[1] : joined[0];

    ASSERT_TRUE(c2->Send(s2, Bytes("c2-reliable"), Delivery::e_reliable));
    ASSERT_TRUE(c2->Send(s2, Bytes("c2-unreliable")));
    ASSERT_TRUE(server->Send(fromC1, Bytes("to-c1-reliable"), Delivery::e_reliable));
    ASSERT_TRUE(server->Send(fromC1, Bytes("to-c1-unreliable")));
    ASSERT_TRUE(server->Send(fromC2, Bytes("to-c2-reliable"), Delivery::e_reliable));
    ASSERT_TRUE(server->Send(fromC2, Bytes("to-c2-unreliable")));
    for (auto& inbox : in) inbox.clear();
    ASSERT_TRUE(Pump({server.get(), c1.get(), c2.get()}, in,
                     [&] { return in[0].size() >= 2 && in[1].size() >= 2 && in[2].size() >= 2; }));
    std::vector<std::string> atServer, atC1, atC2;
    for (const Datagram& d : in[0]) {
        EXPECT_EQ(d.peer, fromC2);
        atServer.push_back(Text(d));
    }
    for (const Datagram& d : in[1]) {
        EXPECT_EQ(d.peer, s1);
        atC1.push_back(Text(d));
    }
    for (const Datagram& d : in[2]) {
        EXPECT_EQ(d.peer, s2);
        atC2.push_back(Text(d));
    }
    std::sort(atServer.begin(), atServer.end());
    std::sort(atC1.begin(), atC1.end());
    std::sort(atC2.begin(), atC2.end());
    EXPECT_EQ(atServer, (std::vector<std::string>{"c2-reliable", "c2-unreliable"}));
    EXPECT_EQ(atC1, (std::vector<std::string>{"to-c1-reliable", "to-c1-unreliable"}));
    EXPECT_EQ(atC2, (std::vector<std::string>{"to-c2-reliable", "to-c2-unreliable"}));

    EXPECT_EQ(c1->Stats().datagramsSent, 2u);
    EXPECT_EQ(c1->Stats().wireBytesSent, 14u + 16u + 2 * EnetTransport::kWireOverhead);
    EXPECT_EQ(server->Stats().datagramsReceived, 4u);
    EXPECT_EQ(server->PacketThrottle(fromC1), kThrottleScale);
    EXPECT_EQ(c1->PacketThrottle(s1), kThrottleScale);
}

TEST(EnetTransportTest, DisconnectIsSeenBothWays) {
    Match m;
    ASSERT_NO_FATAL_FAILURE(Connect(m, 2));
    std::vector<std::vector<Datagram>> in;
    std::vector<PeerId> gone;

    // A graceful disconnect from client 1 frees its id on the server.
    m.c1->Disconnect(m.c1ToServer);
    EXPECT_FALSE(m.c1->IsConnected(m.c1ToServer));
    EXPECT_FALSE(m.c1->Send(m.c1ToServer, Bytes("after")));
    ASSERT_TRUE(Pump(
        {m.server.get(), m.c1.get(), m.c2.get()}, in,
        [&] {
            for (PeerId p : m.server->TakeDisconnected()) gone.push_back(p);
            return !gone.empty();
        },
        2));
    EXPECT_EQ(gone, std::vector<PeerId>{m.serverPeers[0]});
    EXPECT_FALSE(m.server->IsConnected(m.serverPeers[0]));
    EXPECT_TRUE(m.server->IsConnected(m.serverPeers[1]));

    // The server drops client 2: the client sees it.
    m.server->Disconnect(m.serverPeers[1]);
    std::vector<PeerId> clientGone;
    ASSERT_TRUE(Pump(
        {m.server.get(), m.c2.get()}, in,
        [&] {
            for (PeerId p : m.c2->TakeDisconnected()) clientGone.push_back(p);
            return !clientGone.empty();
        },
        2));
    EXPECT_EQ(clientGone, std::vector<PeerId>{m.c2ToServer});
    EXPECT_FALSE(m.c2->IsConnected(m.c2ToServer));
}

TEST(EnetTransportTest, DestroyedClientIsSeenAsDisconnect) {
    Match m;
    ASSERT_NO_FATAL_FAILURE(Connect(m, 1));
    m.c1.reset();  // the destructor tells the server at once
    std::vector<std::vector<Datagram>> in;
    std::vector<PeerId> gone;
    ASSERT_TRUE(Pump(
        {m.server.get()}, in,
        [&] {
            for (PeerId p : m.server->TakeDisconnected()) gone.push_back(p);
            return !gone.empty();
        },
        2));
    EXPECT_EQ(gone, std::vector<PeerId>{m.serverPeers[0]});
}

TEST(EnetTransportTest, UnreliableBurstIsNeverThrottled) {
    Match m;
    ASSERT_NO_FATAL_FAILURE(Connect(m, 1));
    const PeerId toClient = m.serverPeers[0];
    std::vector<Datagram> atServer, atClient;
    const uint32_t n = 2000;
    const auto deadline = Clock::now() + std::chrono::seconds(3);
    uint32_t sent = 0;
    // 20 datagrams each way every 5 ms: a steady ~4,000 datagrams/s, as many per second as 60 Hz
    // inputs from 66 players.
    while ((sent < n || atServer.size() < n || atClient.size() < n) && Clock::now() < deadline) {
        for (int k = 0; k < 20 && sent < n; ++k, ++sent) {
            std::vector<uint8_t> payload(16, static_cast<uint8_t>(sent));
            payload[0] = static_cast<uint8_t>(sent >> 8);
            ASSERT_TRUE(m.c1->Send(m.c1ToServer, payload));
            ASSERT_TRUE(m.server->Send(toClient, payload));
        }
        m.server->Poll(atServer);
        m.c1->Poll(atClient);
        EXPECT_EQ(m.c1->PacketThrottle(m.c1ToServer), kThrottleScale);
        EXPECT_EQ(m.server->PacketThrottle(toClient), kThrottleScale);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_EQ(sent, n);
    EXPECT_EQ(atServer.size(), n);
    EXPECT_EQ(atClient.size(), n);
    std::vector<bool> seen(n, false);
    for (const Datagram& d : atServer) {
        const uint32_t index = uint32_t{d.bytes[0]} << 8 | d.bytes[1];
        ASSERT_LT(index, n);
        EXPECT_FALSE(seen[index]) << "duplicate " << index;
        seen[index] = true;
    }
    EXPECT_EQ(m.c1->Stats().sendFailures, 0u);
    EXPECT_EQ(m.server->Stats().sendFailures, 0u);
}

TEST(EnetTransportTest, InvalidUseGivesErrors) {
    std::string error;
    EXPECT_EQ(EnetTransport::Listen(0, 0, &error), nullptr);
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_EQ(EnetTransport::Listen(0, 4, &error, "not-an-address"), nullptr);
    EXPECT_FALSE(error.empty());
    auto server = EnetTransport::Listen(0, 4, &error);
    ASSERT_NE(server, nullptr) << error;
    error.clear();
    EXPECT_EQ(EnetTransport::Listen(server->LocalPort(), 4, &error), nullptr);  // in use
    EXPECT_FALSE(error.empty());

    auto client = EnetTransport::Client(&error, 1);
    ASSERT_NE(client, nullptr) << error;
    error.clear();
    EXPECT_EQ(client->Connect("localhost", 4000, &error), kNoPeer);  // numeric only
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(client->Connect("127.0.0.1", 0, nullptr), kNoPeer);
    EXPECT_FALSE(client->Send(0, Bytes("x")));
    EXPECT_FALSE(client->Send(kNoPeer, Bytes("x")));

    // A UDP socket that never answers: the connection stays pending, sends wait, up to a bound.
    auto silent = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_NE(silent, nullptr) << error;
    const PeerId p = client->Connect("127.0.0.1", silent->LocalPort(), &error);
    ASSERT_NE(p, kNoPeer) << error;
    EXPECT_EQ(client->Connect("127.0.0.1", silent->LocalPort(), &error), kNoPeer);  // table full
    EXPECT_FALSE(client->IsConnected(p));
    EXPECT_FALSE(client->Send(p, std::vector<uint8_t>(client->MaxDatagram() + 1, 1)));
    EXPECT_FALSE(client->Send(p, std::vector<uint8_t>{}));
    for (size_t i = 0; i < EnetTransport::kMaxPendingPerPeer; ++i) ASSERT_TRUE(client->Send(p, Bytes("queued")));
    EXPECT_FALSE(client->Send(p, Bytes("one too many")));
    EXPECT_EQ(client->Stats().sendFailures, 5u);
    EXPECT_EQ(client->Stats().datagramsSent, EnetTransport::kMaxPendingPerPeer);
    client->Disconnect(p);
    EXPECT_FALSE(client->Send(p, Bytes("x")));
}

TEST(EnetTransportTest, LoopbackRttFigure) {
    // Median of 100 ping-pongs on the unreliable channel (a figure printed, not asserted).
    Match m;
    ASSERT_NO_FATAL_FAILURE(Connect(m, 1));
    const PeerId toClient = m.serverPeers[0];
    std::vector<uint64_t> rtts;
    const std::vector<uint8_t> ping(16, 1);
    std::vector<std::vector<Datagram>> in;
    for (int i = 0; i < 100; ++i) {
        const uint64_t t0 = m.c1->NowMicros();
        ASSERT_TRUE(m.c1->Send(m.c1ToServer, ping));
        for (auto& inbox : in) inbox.clear();
        ASSERT_TRUE(Pump(
            {m.server.get()}, in, [&] { return !in[0].empty(); }, 2));
        ASSERT_TRUE(m.server->Send(toClient, ping));
        for (auto& inbox : in) inbox.clear();
        ASSERT_TRUE(Pump(
            {m.c1.get()}, in, [&] { return !in[0].empty(); }, 2));
        rtts.push_back(m.c1->NowMicros() - t0);
    }
    std::sort(rtts.begin(), rtts.end());
    std::printf(
        "[ figure ] ENet loopback RTT median %llu us (min %llu, max %llu) over 100 pings; ENet's own "
        "estimate %u ms\n",
        static_cast<unsigned long long>(rtts[50]), static_cast<unsigned long long>(rtts.front()),
        static_cast<unsigned long long>(rtts.back()), m.c1->RoundTripMillis(m.c1ToServer));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
