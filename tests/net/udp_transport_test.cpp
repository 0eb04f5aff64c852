// UdpTransport on loopback (127.0.0.1 and ::1 only): round trips, admission, limits, errors.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include "lockbox/net/UdpTransport.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

using Clock = std::chrono::steady_clock;

// Polls until `want` datagrams have arrived or 2 s have passed; every wait is bounded.
std::vector<Datagram> Receive(UdpTransport& t, size_t want) {
    std::vector<Datagram> got;
    const auto deadline = Clock::now() + std::chrono::seconds(2);
    while (got.size() < want && Clock::now() < deadline) {
        if (t.Poll(got) == 0) t.WaitReadable(20);
    }
    return got;
}

std::vector<uint8_t> Bytes(const std::string& text) { return std::vector<uint8_t>(text.begin(), text.end()); }

std::string Text(const Datagram& d) { return std::string(d.bytes.begin(), d.bytes.end()); }

void RoundTrip(const std::string& host, uint64_t overhead) {
    std::string error;
    auto server = UdpTransport::Open(host, 0, &error);
    ASSERT_NE(server, nullptr) << error;
    auto client = UdpTransport::Open(host, 0, &error);
    ASSERT_NE(client, nullptr) << error;
    ASSERT_NE(server->LocalPort(), 0);
    const PeerId toServer = client->AddPeer(host, server->LocalPort(), &error);
    ASSERT_NE(toServer, kNoPeer) << error;
    EXPECT_EQ(client->AddPeer(host, server->LocalPort(), &error), toServer);  // known address

    ASSERT_TRUE(client->Send(toServer, Bytes("hello")));
    auto atServer = Receive(*server, 1);
    ASSERT_EQ(atServer.size(), 1u);
    EXPECT_EQ(Text(atServer[0]), "hello");
    const PeerId toClient = atServer[0].peer;
    EXPECT_EQ(toClient, 0u);  // an unknown sender is admitted under the first free id
    EXPECT_FALSE(server->PeerAddress(toClient).empty());

    ASSERT_TRUE(server->Send(toClient, Bytes("world"), Delivery::e_reliable));
    auto atClient = Receive(*client, 1);
    ASSERT_EQ(atClient.size(), 1u);
    EXPECT_EQ(Text(atClient[0]), "world");
    EXPECT_EQ(atClient[0].peer, toServer);

    EXPECT_EQ(client->Stats().datagramsSent, 1u);
    EXPECT_EQ(client->Stats().wireBytesSent, 5u + overhead);
    EXPECT_EQ(server->Stats().datagramsReceived, 1u);
    EXPECT_EQ(server->Stats().payloadBytesReceived, 5u);
    EXPECT_GT(client->NowMicros(), 0u);
}

TEST(UdpTransportTest, LoopbackIpv4RoundTrip) { RoundTrip("127.0.0.1", UdpTransport::kIpv4Overhead); }

TEST(UdpTransportTest, LoopbackIpv6RoundTrip) {
    std::string error;
    if (UdpTransport::Open("::1", 0, &error) == nullptr) GTEST_SKIP() << "no IPv6 loopback: " << error;
    RoundTrip("::1", UdpTransport::kIpv6Overhead);
}

TEST(UdpTransportTest, Ipv6SocketTakesIpv4Clients) {
    // Bound to the IPv4-mapped loopback (not "::"), so the socket never leaves loopback.
    std::string error;
    auto server = UdpTransport::Open("::ffff:127.0.0.1", 0, &error);
    if (server == nullptr) GTEST_SKIP() << "no IPv4-mapped IPv6 sockets: " << error;
    ASSERT_TRUE(server->IsIpv6());
    auto client = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_NE(client, nullptr) << error;
    const PeerId toServer = client->AddPeer("127.0.0.1", server->LocalPort(), &error);
    ASSERT_NE(toServer, kNoPeer) << error;
    ASSERT_TRUE(client->Send(toServer, Bytes("v4")));
    auto got = Receive(*server, 1);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_NE(server->PeerAddress(got[0].peer).find("::ffff:127.0.0.1"), std::string::npos)
        << server->PeerAddress(got[0].peer);
    ASSERT_TRUE(server->Send(got[0].peer, Bytes("back")));
    EXPECT_EQ(server->Stats().wireBytesSent, 4u + UdpTransport::kIpv4Overhead);  // IPv4 on the wire
    auto back = Receive(*client, 1);
    ASSERT_EQ(back.size(), 1u);
    EXPECT_EQ(Text(back[0]), "back");
    // The same client added by hand maps to the same peer.
    EXPECT_EQ(server->AddPeer("127.0.0.1", client->LocalPort(), &error), got[0].peer);
}

TEST(UdpTransportTest, ManyDatagramsBothWays) {
    std::string error;
    auto a = UdpTransport::Open("127.0.0.1", 0, &error);
    auto b = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_TRUE(a && b) << error;
    const PeerId ab = a->AddPeer("127.0.0.1", b->LocalPort(), &error);
    const PeerId ba = b->AddPeer("127.0.0.1", a->LocalPort(), &error);
    ASSERT_TRUE(ab != kNoPeer && ba != kNoPeer) << error;
    for (uint32_t i = 0; i < 200; ++i) {
        std::vector<uint8_t> payload(1 + i % 300, static_cast<uint8_t>(i));
        ASSERT_TRUE(a->Send(ab, payload));
        ASSERT_TRUE(b->Send(ba, payload));
    }
    auto atB = Receive(*b, 200);
    auto atA = Receive(*a, 200);
    ASSERT_EQ(atB.size(), 200u);
    ASSERT_EQ(atA.size(), 200u);
    for (uint32_t i = 0; i < 200; ++i) {
        // Loopback keeps order; check content and size anyway.
        EXPECT_EQ(atB[i].bytes.size(), 1 + i % 300);
        EXPECT_EQ(atB[i].bytes[0], static_cast<uint8_t>(i));
        EXPECT_EQ(atA[i].peer, ab);
    }
}

TEST(UdpTransportTest, MaxPeersEnforcedAndDisconnectFreesSlot) {
    std::string error;
    auto server = UdpTransport::Open("127.0.0.1", 0, &error, 2);
    ASSERT_NE(server, nullptr) << error;
    std::vector<std::unique_ptr<UdpTransport>> clients;
    std::vector<PeerId> toServer;
    for (int i = 0; i < 3; ++i) {
        clients.push_back(UdpTransport::Open("127.0.0.1", 0, &error));
        ASSERT_NE(clients.back(), nullptr) << error;
        toServer.push_back(clients.back()->AddPeer("127.0.0.1", server->LocalPort(), &error));
        ASSERT_NE(toServer.back(), kNoPeer) << error;
    }
    for (int i = 0; i < 3; ++i) {
        ASSERT_TRUE(clients[i]->Send(toServer[i], Bytes(std::to_string(i))));
        // One at a time, so admission order (and thus the ids) is fixed.
        if (i < 2) {
            ASSERT_EQ(Receive(*server, 1).size(), 1u);
        }
    }
    const auto deadline = Clock::now() + std::chrono::seconds(2);
    while (server->Stats().droppedUnknown == 0 && Clock::now() < deadline) {
        std::vector<Datagram> none;
        if (server->Poll(none) == 0) server->WaitReadable(20);
        ASSERT_TRUE(none.empty());
    }
    EXPECT_EQ(server->Stats().droppedUnknown, 1u);
    EXPECT_EQ(server->PeerCount(), 2u);
    EXPECT_EQ(server->AddPeer("127.0.0.1", 9, &error), kNoPeer);
    EXPECT_NE(error.find("full"), std::string::npos) << error;

    server->Disconnect(0);
    EXPECT_FALSE(server->Send(0, Bytes("gone")));
    ASSERT_TRUE(clients[2]->Send(toServer[2], Bytes("again")));
    auto got = Receive(*server, 1);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(Text(got[0]), "again");
    EXPECT_EQ(got[0].peer, 0u);  // the freed slot
}

TEST(UdpTransportTest, OversizeAndInvalidSendsRefused) {
    std::string error;
    auto a = UdpTransport::Open("127.0.0.1", 0, &error);
    auto b = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_TRUE(a && b) << error;
    const PeerId ab = a->AddPeer("127.0.0.1", b->LocalPort(), &error);
    EXPECT_FALSE(a->Send(ab, std::vector<uint8_t>(a->MaxDatagram() + 1, 1)));
    EXPECT_FALSE(a->Send(ab, std::vector<uint8_t>{}));
    EXPECT_FALSE(a->Send(ab + 1, Bytes("x")));
    EXPECT_FALSE(a->Send(kNoPeer, Bytes("x")));
    EXPECT_EQ(a->Stats().sendFailures, 4u);
    EXPECT_TRUE(a->Send(ab, std::vector<uint8_t>(a->MaxDatagram(), 1)));
    EXPECT_EQ(Receive(*b, 1).size(), 1u);

    // A raw socket sends what no UdpTransport would: the receiver drops it and counts it.
    const int raw = ::socket(AF_INET, SOCK_DGRAM, 0);
    ASSERT_GE(raw, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(b->LocalPort());
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const std::vector<uint8_t> big(1500, 9);
    EXPECT_EQ(::sendto(raw, big.data(), big.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to)), 1500);
    EXPECT_EQ(::sendto(raw, big.data(), 0, 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to)), 0);
    ::close(raw);
    const auto deadline = Clock::now() + std::chrono::seconds(2);
    std::vector<Datagram> got;
    while (b->DroppedMalformed() < 2 && Clock::now() < deadline) {
        if (b->Poll(got) == 0) b->WaitReadable(20);
    }
    EXPECT_EQ(b->DroppedMalformed(), 2u);
    EXPECT_TRUE(got.empty());
    EXPECT_EQ(b->PeerCount(), 1u);  // only a: a malformed datagram admits nobody
}

TEST(UdpTransportTest, BadAddressesGiveErrors) {
    std::string error;
    EXPECT_EQ(UdpTransport::Open("not-an-address", 0, &error), nullptr);
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_EQ(UdpTransport::Open("127.0.0.1", 0, &error, 0), nullptr);
    EXPECT_FALSE(error.empty());

    auto a = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_NE(a, nullptr) << error;
    error.clear();
    EXPECT_EQ(UdpTransport::Open("127.0.0.1", a->LocalPort(), &error), nullptr);  // in use
    EXPECT_NE(error.find("bind"), std::string::npos) << error;
    error.clear();
    EXPECT_EQ(a->AddPeer("999.1.2.3", 4000, &error), kNoPeer);
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_EQ(a->AddPeer("localhost", 4000, &error), kNoPeer);  // numeric addresses only
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_EQ(a->AddPeer("::1", 4000, &error), kNoPeer);  // IPv6 on an IPv4 socket
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_EQ(a->AddPeer("127.0.0.1", 0, &error), kNoPeer);
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(a->AddPeer("", 4000, nullptr), kNoPeer);  // a null error pointer is fine
    EXPECT_EQ(a->PeerCount(), 0u);
}

TEST(UdpTransportTest, LoopbackRttFigure) {
    // Median of 100 ping-pongs (a figure printed, not asserted).
    std::string error;
    auto a = UdpTransport::Open("127.0.0.1", 0, &error);
    auto b = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_TRUE(a && b) << error;
    const PeerId ab = a->AddPeer("127.0.0.1", b->LocalPort(), &error);
    const PeerId ba = b->AddPeer("127.0.0.1", a->LocalPort(), &error);
    std::vector<uint64_t> rtts;
    const std::vector<uint8_t> ping(16, 1);
    for (int i = 0; i < 100; ++i) {
        const uint64_t t0 = a->NowMicros();
        ASSERT_TRUE(a->Send(ab, ping));
        ASSERT_EQ(Receive(*b, 1).size(), 1u);
        ASSERT_TRUE(b->Send(ba, ping));
        ASSERT_EQ(Receive(*a, 1).size(), 1u);
        rtts.push_back(a->NowMicros() - t0);
    }
    std::sort(rtts.begin(), rtts.end());
    std::printf("[ figure ] UDP loopback RTT median %llu us (min %llu, max %llu) over 100 pings\n",
                static_cast<unsigned long long>(rtts[50]), static_cast<unsigned long long>(rtts.front()),
                static_cast<unsigned long long>(rtts.back()));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
