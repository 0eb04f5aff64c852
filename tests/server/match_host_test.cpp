// MatchHost over real loopback UDP, in one process: matches for admitted clients, every kind of
// refused token counted and never answered, no amplification before the handshake, the rate
// limit, the drain, and the replay of a finished match.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "MatchHost.h"
#include "Metrics.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "server_harness.h"

namespace lockbox::server {
namespace LOCKBOX_TEST_FILE {

using testing::kNow;
using testing::Mint;
using testing::TestClient;

constexpr int32_t kFrames = 120;

// Every host of these tests plays 2-player matches at a fast tick, which keeps the wall time
// short.
struct Host : testing::TestHost {
    explicit Host(HostConfig config = {}) : testing::TestHost(FastTwoPlayer(std::move(config))) {}
    static HostConfig FastTwoPlayer(HostConfig config) {
        config.match.playerCount = 2;
        config.match.tickRate = 240;
        config.match.hashInterval = 20;
        return config;
    }
};

uint64_t Refused(const MatchHost& h, admission::Refusal r) { return h.Stats().refusedTokens[static_cast<size_t>(r)]; }
using testing::Dropped;

TEST(MatchHost, TwoMatchesOnOnePortPlayAndAgree) {
    Host h;
    std::vector<std::unique_ptr<TestClient>> clients;
    for (uint32_t match = 1; match <= 2; ++match)
        for (uint8_t slot = 0; slot < 2; ++slot)
            clients.push_back(std::make_unique<TestClient>(h.port, Mint(match, slot, match * 10 + slot),
                                                           500 + clients.size(), kFrames - 1));
    testing::Pump([&] { h.host->Update(); }, clients,
                  [&] {
                      for (auto& c : clients)
                          if (c->client->Frame() < kFrames) return false;
                      return true;
                  });
    for (size_t i = 0; i < clients.size(); ++i) {
        EXPECT_GE(clients[i]->client->Frame(), kFrames) << "client " << i;
        EXPECT_EQ(clients[i]->client->Slot(), static_cast<int32_t>(i % 2)) << "client " << i;
    }
    EXPECT_EQ(clients[0]->worldHash, clients[1]->worldHash);
    EXPECT_EQ(clients[2]->worldHash, clients[3]->worldHash);
    EXPECT_EQ(h.host->MatchCount(), 2u);
    EXPECT_EQ(h.host->PlayerCount(), 4u);
    EXPECT_EQ(h.host->Stats().admitted, 4u);
    EXPECT_EQ(h.host->Stats().desyncs, 0u);
    const std::string metrics = RenderMetrics(*h.host);
    EXPECT_NE(metrics.find("lockbox_server_matches 2\n"), std::string::npos) << metrics;
    EXPECT_NE(metrics.find("lockbox_server_refused_tokens_total{reason=\"forged\"} 0\n"), std::string::npos);
    EXPECT_NE(metrics.find("lockbox_server_tick_seconds{quantile=\"0.99\"}"), std::string::npos);
}

// A raw socket that sends datagrams to the host and counts what comes back.
struct RawSender {
    std::unique_ptr<net::UdpTransport> udp;
    net::PeerId server = net::kNoPeer;
    uint64_t bytesSent = 0, bytesReceived = 0;

    explicit RawSender(uint16_t port) {
        std::string error;
        udp = net::UdpTransport::Open("127.0.0.1", 0, &error);
        server = udp->AddPeer("127.0.0.1", port, &error);
    }
    void Send(std::span<const uint8_t> bytes) {
        ASSERT_TRUE(udp->Send(server, bytes));
        bytesSent += bytes.size();
    }
    void SendToken(const admission::TokenBytes& token, std::span<const uint8_t> payload) {
        std::vector<uint8_t> out;
        net::admission::WriteEnvelope(out, token, payload);
        Send(out);
    }
    void Drain() {
        std::vector<net::Datagram> got;
        udp->Poll(got);
        for (const auto& d : got) bytesReceived += d.bytes.size();
    }
};

// A Hello datagram as a LockstepClient sends it first.
std::vector<uint8_t> HelloBytes() {
    net::DatagramWriter w;
    w.Begin(net::Header{net::kProtocolVersion, 0, 0});
    w.Add(net::Hello{b2_determinismVersion, 0, net::kAnySlot, 0}, net::SessionShape{});
    return {w.Bytes().begin(), w.Bytes().end()};
}

void Settle(MatchHost& host, std::vector<RawSender*> senders) {
    for (int i = 0; i < 50; ++i) {
        host.Update();
        for (RawSender* s : senders) s->Drain();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

TEST(MatchHost, RefusesEveryBadTokenUnanswered) {
    HostConfig config;
    config.matchIds = {1, 2};
    config.tokenMaxLifetimeSeconds = 600;
    Host h(std::move(config));
    const std::vector<uint8_t> hello = HelloBytes();
    RawSender plain(h.port), forged(h.port), expired(h.port), tooLong(h.port), wrongMatch(h.port), wrongSlot(h.port),
        version(h.port), first(h.port), copy(h.port);
    plain.Send(hello);  // no envelope at all
    forged.SendToken(Mint(1, 0, 1, kNow + 60, admission::TokenKey{}), hello);
    expired.SendToken(Mint(1, 0, 2, kNow), hello);
    tooLong.SendToken(Mint(1, 0, 3, kNow + 601), hello);
    wrongMatch.SendToken(Mint(3, 0, 4), hello);
    wrongSlot.SendToken(Mint(1, 2, 5), hello);  // the matches have 2 slots
    admission::TokenBytes otherVersion = Mint(1, 0, 6);
    otherVersion[2] = 7;
    version.SendToken(otherVersion, hello);
    first.SendToken(Mint(2, 0, 7), hello);  // admitted
    Settle(*h.host, {&plain, &forged, &expired, &tooLong, &wrongMatch, &wrongSlot, &version, &first});
    copy.SendToken(Mint(2, 0, 7), hello);  // the same token from another address
    Settle(*h.host, {&copy, &first});

    const MatchHost& m = *h.host;
    EXPECT_EQ(Dropped(m, Drop::e_noToken), 1u);
    EXPECT_EQ(Refused(m, admission::Refusal::e_forged), 1u);
    EXPECT_EQ(Refused(m, admission::Refusal::e_expired), 1u);
    EXPECT_EQ(Refused(m, admission::Refusal::e_tooLong), 1u);
    EXPECT_EQ(Refused(m, admission::Refusal::e_wrongMatch), 2u);
    EXPECT_EQ(Refused(m, admission::Refusal::e_badVersion), 1u);
    EXPECT_EQ(Refused(m, admission::Refusal::e_reused), 1u);
    EXPECT_EQ(m.Stats().admitted, 1u);
    EXPECT_EQ(m.MatchCount(), 1u);
    for (RawSender* s : {&plain, &forged, &expired, &tooLong, &wrongMatch, &wrongSlot, &version, &copy})
        EXPECT_EQ(s->bytesReceived, 0u);
    // The admitted sender got its Welcome, and no more bytes than it sent.
    EXPECT_GT(first.bytesReceived, 0u);
    EXPECT_LE(first.bytesReceived, first.bytesSent);
}

TEST(MatchHost, NeverSendsMoreThanItReceivedBeforeTheHandshake) {
    Host h;
    const std::vector<uint8_t> hello = HelloBytes();
    RawSender s(h.port);
    // A sender that presents a valid token but never completes the handshake: its Hellos are
    // resent, the server answers each, never with more bytes than came in.
    for (int i = 0; i < 20; ++i) {
        s.SendToken(Mint(1, 0, 1), hello);
        Settle(*h.host, {&s});
        EXPECT_LE(s.bytesReceived, s.bytesSent) << "after " << i + 1 << " Hellos";
    }
    EXPECT_GT(s.bytesReceived, 0u);
    // Keep the match turning for a while: keep-alives and resends stay within the budget too.
    Settle(*h.host, {&s});
    Settle(*h.host, {&s});
    EXPECT_LE(s.bytesReceived, s.bytesSent);
}

TEST(MatchHost, RateLimitsUnadmittedSourcesPerAddress) {
    HostConfig config;
    config.rateLimitPerSecond = 10;
    config.rateLimitBurst = 5;
    Host h(std::move(config));
    // Many source ports of one address share one bucket.
    std::vector<std::unique_ptr<RawSender>> senders;
    for (int i = 0; i < 20; ++i) senders.push_back(std::make_unique<RawSender>(h.port));
    const std::vector<uint8_t> junk(40, 0xAB);
    for (auto& s : senders)
        for (int k = 0; k < 5; ++k) s->Send(junk);
    std::vector<RawSender*> all;
    for (auto& s : senders) all.push_back(s.get());
    Settle(*h.host, all);
    const uint64_t limited = Dropped(*h.host, Drop::e_rateLimited);
    const uint64_t unread = Dropped(*h.host, Drop::e_noToken);
    EXPECT_EQ(limited + unread, 100u);
    EXPECT_GE(unread, 5u);
    EXPECT_LE(unread, 7u);  // the burst, plus what the clock refilled meanwhile
    for (auto& s : senders) EXPECT_EQ(s->bytesReceived, 0u);
}

TEST(MatchHost, DrainingRefusesNewClients) {
    Host h;
    h.host->BeginDrain();
    RawSender s(h.port);
    s.SendToken(Mint(1, 0, 1), HelloBytes());
    Settle(*h.host, {&s});
    EXPECT_EQ(Dropped(*h.host, Drop::e_draining), 1u);
    EXPECT_EQ(s.bytesReceived, 0u);
    EXPECT_EQ(h.host->MatchCount(), 0u);
}

TEST(MatchHost, WritesTheReplayOfAClosedMatchAndItAgreesWithTheClients) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lockbox_server_replay_test";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    HostConfig config;
    config.scene = "vertical_stack";
    config.replayDir = dir.string();
    Host h(std::move(config));
    std::vector<std::unique_ptr<TestClient>> clients;
    for (uint8_t slot = 0; slot < 2; ++slot)
        clients.push_back(std::make_unique<TestClient>(h.port, Mint(9, slot, 90 + slot), 700 + slot, kFrames - 1));
    testing::Pump([&] { h.host->Update(); }, clients,
                  [&] { return clients[0]->client->Frame() >= kFrames && clients[1]->client->Frame() >= kFrames; });
    ASSERT_EQ(clients[0]->worldHash, clients[1]->worldHash);
    h.host->CloseAll();
    EXPECT_EQ(h.host->Stats().replaysWritten, 1u);
    EXPECT_EQ(h.host->MatchCount(), 0u);

    replay::ReplayFile file;
    ASSERT_TRUE(replay::LoadReplay((dir / "match-9.lbr").string(), file).ok());
    EXPECT_GE(file.frameCount, kFrames);
    replay::SceneGame game("vertical_stack");
    replay::Player player(file, game.world(), game);
    const replay::VerifyResult verified = player.Verify();
    EXPECT_TRUE(verified.ok) << verified.message;
    // The replay's state after kFrames frames is the clients'.
    ASSERT_TRUE(player.Seek(kFrames).ok());
    EXPECT_EQ(player.world().Hash(), clients[0]->worldHash);
    std::filesystem::remove_all(dir);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::server

namespace lockbox::server {
namespace LOCKBOX_TEST_FILE {

// Two matches play while sixteen source ports of the same address flood the port with junk,
// forged, expired and copied tokens: the matches finish and agree, nothing is answered, every
// flood datagram is counted under one reason, and the socket's peer table does not grow.
TEST(MatchHost, MatchesPlayOnThroughAFloodAndEveryDropIsCounted) {
    Host h;
    std::vector<std::unique_ptr<TestClient>> clients;
    for (uint32_t match = 1; match <= 2; ++match)
        for (uint8_t slot = 0; slot < 2; ++slot)
            clients.push_back(std::make_unique<TestClient>(h.port, Mint(match, slot, match * 10 + slot),
                                                           800 + clients.size(), kFrames - 1));
    // The clients get in first (the flood shares their address, and the rate limit is per address).
    testing::Pump([&] { h.host->Update(); }, clients,
                  [&] {
                      for (auto& c : clients)
                          if (c->client->Frame() < 1) return false;
                      return true;
                  });
    ASSERT_EQ(h.host->PlayerCount(), 4u);

    std::vector<std::unique_ptr<RawSender>> flood;
    for (int i = 0; i < 16; ++i) flood.push_back(std::make_unique<RawSender>(h.port));
    const std::vector<uint8_t> hello = HelloBytes();
    uint64_t sent = 0, counter = 12345;
    std::vector<uint8_t> junk;
    testing::Pump(
        [&] {
            for (size_t i = 0; i < flood.size(); ++i) {
                counter = counter * 6364136223846793005ull + 1442695040888963407ull;
                switch (counter >> 62) {
                    case 0:
                        junk.assign(1 + (counter >> 8) % 200, static_cast<uint8_t>(counter >> 16));
                        flood[i]->Send(junk);
                        break;
                    case 1: flood[i]->SendToken(Mint(1, 0, 10), hello); break;                 // a copy of a live token
                    case 2: flood[i]->SendToken(Mint(1, 1, counter, kNow - 1), hello); break;  // expired
                    default: flood[i]->SendToken(Mint(2, 0, counter, kNow + 60, admission::TokenKey{}), hello);
                }
                ++sent;
            }
            h.host->Update();
        },
        clients,
        [&] {
            for (auto& c : clients)
                if (c->client->Frame() < kFrames) return false;
            return true;
        });
    Settle(*h.host, {});
    for (size_t i = 0; i < clients.size(); ++i) EXPECT_GE(clients[i]->client->Frame(), kFrames) << "client " << i;
    EXPECT_EQ(clients[0]->worldHash, clients[1]->worldHash);
    EXPECT_EQ(clients[2]->worldHash, clients[3]->worldHash);
    for (auto& f : flood) {
        f->Drain();
        EXPECT_EQ(f->bytesReceived, 0u);
    }
    const HostStats& s = h.host->Stats();
    uint64_t counted = 0;
    for (uint64_t n : s.refusedTokens) counted += n;
    for (uint64_t n : s.dropped) counted += n;
    EXPECT_GT(sent, 400u);  // a few hundred under a sanitizer on a loaded machine, thousands in release
    EXPECT_EQ(counted, sent);
    EXPECT_GT(Dropped(*h.host, Drop::e_rateLimited), 0u);
    EXPECT_EQ(s.admitted, 4u);
    // Refused senders leave the socket's table at once: only the four clients remain.
    EXPECT_EQ(h.host->Socket().PeerCount(), 4u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::server
