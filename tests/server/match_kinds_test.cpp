// The match kinds besides the lockstep relay, over real loopback UDP through MatchHost: an
// authoritative lockstep match (the server simulates the scene and its hash agrees with the
// clients'), rollback peers through the server's relay (the server records their inputs and the
// replay equals the peers' confirmed state), the relay slot the token names, and the per-peer
// bandwidth limit (a player's, and the larger one of the player that hosts the spectators), and
// spectators taking a relay slot in turn.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "MatchHost.h"
#include "lockbox/net/RelayWire.h"
#include "lockbox/net/RelayedTransport.h"
#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackSpectator.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/net/admission/AdmissionTransport.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "server_harness.h"

namespace lockbox::server {
namespace LOCKBOX_TEST_FILE {

namespace fs = std::filesystem;
using testing::kNow;
using testing::Mint;
using testing::TestClient;

constexpr int32_t kFrames = 120;

using Host = testing::TestHost;
using testing::Dropped;

fs::path FreshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(MatchKinds, AuthoritativeLockstepSimulatesAndAgreesWithItsClients) {
    const fs::path dir = FreshDir("lockbox_server_authoritative_test");
    HostConfig config;
    config.kind = MatchKind::e_lockstepAuthoritative;
    config.scene = "vertical_stack";
    config.replayDir = dir.string();
    config.match.playerCount = 2;
    config.match.tickRate = 240;
    config.match.hashInterval = 20;
    Host h(std::move(config));
    std::vector<std::unique_ptr<TestClient>> clients;
    for (uint8_t slot = 0; slot < 2; ++slot)
        clients.push_back(std::make_unique<TestClient>(h.port, Mint(3, slot, 30 + slot), 500 + slot, kFrames - 1));
    testing::Pump([&] { h.host->Update(); }, clients,
                  [&] {
                      const net::LockstepServer* s = h.host->LockstepOf(3);
                      return clients[0]->client->Frame() >= kFrames && clients[1]->client->Frame() >= kFrames &&
                             s != nullptr && s->SimulatedFrames() >= kFrames;
                  });
    ASSERT_GE(clients[1]->client->Frame(), kFrames);
    const net::LockstepServer* server = h.host->LockstepOf(3);
    ASSERT_NE(server, nullptr);
    // The server stepped the scene itself and compared its hashes with the clients'.
    EXPECT_GE(server->SimulatedFrames(), kFrames);
    EXPECT_EQ(server->Stats().desyncFrames, 0u);
    EXPECT_EQ(h.host->Stats().desyncs, 0u);
    EXPECT_EQ(clients[0]->worldHash, clients[1]->worldHash);
    h.host->CloseAll();
    ASSERT_EQ(h.host->Stats().replaysWritten, 1u);
    replay::ReplayFile file;
    ASSERT_TRUE(replay::LoadReplay((dir / "match-3.lbr").string(), file).ok());
    replay::SceneGame game("vertical_stack");
    replay::Player player(file, game.world(), game);
    const replay::VerifyResult verified = player.Verify();
    EXPECT_TRUE(verified.ok) << verified.message;
    ASSERT_TRUE(player.Seek(kFrames).ok());
    EXPECT_EQ(player.world().Hash(), clients[0]->worldHash);
    fs::remove_all(dir);
}

// A rollback peer of a relayed match: UDP, the admission envelope, the relay's framing, the
// session on the scene's world.
struct RollbackClient {
    std::unique_ptr<net::UdpTransport> udp;
    std::unique_ptr<net::admission::AdmissionTransport> admission;
    std::unique_ptr<net::RelayedTransport> relayed;
    std::unique_ptr<replay::SceneGame> game;
    std::unique_ptr<net::WorldGameAdapter> adapter;
    std::unique_ptr<net::RollbackSession> session;
    std::unique_ptr<net::RollbackPeer> peer;
    std::unique_ptr<replay::ScriptedInputs> inputs;
    std::vector<uint8_t> pending;
    std::vector<uint8_t> snapshot;
    uint32_t slot = 0;

    /// `spectatorSlots` > 0: this peer hosts late-join spectators at the relay slots after the
    /// players' (slots = players + spectatorSlots).
    RollbackClient(uint16_t port, uint32_t match, uint32_t claimSlot, uint32_t players,
                   const admission::TokenBytes& token, uint64_t seed, uint32_t spectatorSlots = 0)
        : slot(claimSlot) {
        std::string error;
        udp = net::UdpTransport::Open("127.0.0.1", 0, &error);
        EXPECT_TRUE(udp) << error;
        const net::PeerId server = udp->AddPeer("127.0.0.1", port, &error);
        admission = std::make_unique<net::admission::AdmissionTransport>(*udp, server, token);
        relayed = std::make_unique<net::RelayedTransport>(
            *admission, net::RelayedTransportConfig{server, match, claimSlot, players + spectatorSlots, 0, 20000});
        game = std::make_unique<replay::SceneGame>("vertical_stack");
        const auto& info = game->info();
        adapter = std::make_unique<net::WorldGameAdapter>(
            game->world(), *game,
            WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                              static_cast<uint32_t>(info.positionIterations)});
        session = net::RollbackSessionBuilder()
                      .Players(players)
                      .InputBytes(replay::SceneInput::kBytes)
                      .LocalPlayer(claimSlot)
                      .InputDelay(2)
                      .DesyncInterval(20)
                      .Build();
        net::RollbackPeerConfig cfg;
        cfg.matchId = match;
        for (uint32_t j = 0; j < players; ++j)
            if (j != claimSlot) cfg.remotes.push_back(net::RollbackRemote{j, {j}});
        cfg.maxLateSpectators = spectatorSlots;
        cfg.lateSpectatorTimeoutMicros = 300'000;
        peer = std::make_unique<net::RollbackPeer>(*session, *relayed, cfg);
        inputs = std::make_unique<replay::ScriptedInputs>(seed, 1);
    }

    void Step(int32_t stopAt) {
        peer->Poll();
        if (!peer->WaitThisTick() && session->CurrentFrame() < stopAt) {
            if (pending.empty()) inputs->Next(pending);
            if (session->AddLocalInput(slot, pending) != net::InputResult::e_alreadyAdded) pending.clear();
            (void)adapter->Execute(*session, session->AdvanceFrame());
            int32_t f = 0;
            if (peer->SnapshotWanted() && adapter->ConfirmedSnapshot(*session, f, snapshot))
                (void)peer->OfferSnapshot(f, snapshot);
        }
        peer->Flush();
    }
};

TEST(MatchKinds, RollbackPeersPlayThroughTheRelayAndTheReplayIsTheirs) {
    const fs::path dir = FreshDir("lockbox_server_rollback_test");
    HostConfig config;
    config.kind = MatchKind::e_rollbackRelay;
    config.scene = "vertical_stack";
    config.replayDir = dir.string();
    config.match.playerCount = 2;
    config.match.inputBytes = replay::SceneInput::kBytes;
    config.match.hashInterval = 20;
    config.peerBytesPerSecond = 0;  // the test's loop flushes far faster than a game's tick
    Host h(std::move(config));
    std::vector<std::unique_ptr<RollbackClient>> peers;
    for (uint32_t slot = 0; slot < 2; ++slot)
        peers.push_back(std::make_unique<RollbackClient>(h.port, 11, slot, 2,
                                                         Mint(11, static_cast<uint8_t>(slot), 110 + slot), 900 + slot));
    // A client whose token names slot 1 but whose relay link claims slot 0 is never seated.
    RollbackClient impostor(h.port, 11, 0, 2, Mint(11, 1, 119), 999);
    const int32_t target = kFrames + 40;  // the peers confirm kFrames once both reached it
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
        h.host->Update();
        for (auto& p : peers) p->Step(target);
        impostor.peer->Poll();
        impostor.peer->Flush();
        if (peers[0]->session->ConfirmedFrame() >= kFrames && peers[1]->session->ConfirmedFrame() >= kFrames) break;
        std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    ASSERT_GE(peers[0]->session->ConfirmedFrame(), kFrames);
    ASSERT_GE(peers[1]->session->ConfirmedFrame(), kFrames);
    EXPECT_GT(Dropped(*h.host, Drop::e_wrongSlot), 0u);
    // The peers' final hashes (frames that are multiples of 20) agree.
    std::map<int32_t, uint64_t> finals;
    for (const auto& [f, hash] : peers[0]->session->FinalHashes()) finals[f] = hash;
    size_t compared = 0;
    for (const auto& [f, hash] : peers[1]->session->FinalHashes())
        if (finals.count(f) != 0) {
            EXPECT_EQ(finals[f], hash) << "frame " << f;
            ++compared;
        }
    EXPECT_GT(compared, 0u);
    h.host->CloseAll();
    ASSERT_EQ(h.host->Stats().replaysWritten, 1u);
    replay::ReplayFile file;
    ASSERT_TRUE(replay::LoadReplay((dir / "match-11.lbr").string(), file).ok());
    EXPECT_GE(file.frameCount, kFrames);
    replay::SceneGame game("vertical_stack");
    replay::Player player(file, game.world(), game);
    const replay::VerifyResult verified = player.Verify();
    EXPECT_TRUE(verified.ok) << verified.message;
    // The replay holds the peers' confirmed frames: its state equals their final hashes.
    size_t matched = 0;
    for (const auto& [f, hash] : finals) {
        if (f > file.frameCount || f == 0) continue;
        ASSERT_TRUE(player.Seek(f).ok());
        EXPECT_EQ(player.world().Hash(), hash) << "frame " << f;
        ++matched;
    }
    EXPECT_GT(matched, 0u);
    fs::remove_all(dir);
}

// A spectator of a relayed match, joining late from peer 0's snapshot.
struct Watcher {
    std::unique_ptr<net::UdpTransport> udp;
    std::unique_ptr<net::admission::AdmissionTransport> admission;
    std::unique_ptr<net::RelayedTransport> relayed;
    std::unique_ptr<replay::SceneGame> game;
    std::unique_ptr<net::RollbackSpectator> spectator;
    std::map<int32_t, uint64_t> hashes;  // frame f (f % 20 == 0) -> world hash there
    int32_t frames = 0;                  // frames applied (the next one to apply)

    Watcher(uint16_t port, uint32_t match, uint32_t slot, uint32_t slots, const admission::TokenBytes& token) {
        std::string error;
        udp = net::UdpTransport::Open("127.0.0.1", 0, &error);
        const net::PeerId server = udp->AddPeer("127.0.0.1", port, &error);
        admission = std::make_unique<net::admission::AdmissionTransport>(*udp, server, token);
        relayed = std::make_unique<net::RelayedTransport>(
            *admission, net::RelayedTransportConfig{server, match, slot, slots, 0, 20000});
        game = std::make_unique<replay::SceneGame>("vertical_stack");
        net::RollbackSpectatorConfig sc;
        sc.matchId = match;
        sc.players = 2;
        sc.inputBytes = replay::SceneInput::kBytes;
        sc.host = 0;
        sc.lateJoin = true;
        spectator = std::make_unique<net::RollbackSpectator>(*relayed, sc);
    }

    void Step() {
        spectator->Poll();
        int32_t f = 0;
        std::vector<uint8_t> bytes;
        if (spectator->TakeSnapshot(f, bytes)) {
            EXPECT_TRUE(net::WorldGameAdapter::RestoreSnapshot(game->world(), *game, bytes));
            frames = f;
        }
        const auto& info = game->info();
        while (spectator->Next(f, bytes)) {
            game->Apply(game->world(), f, bytes);
            game->world().Step(Fixed::FromRatio(1, info.hz), info.velocityIterations, info.positionIterations);
            frames = f + 1;
            if (frames % 20 == 0) hashes[frames] = game->world().Hash();
        }
        spectator->Flush();
    }
};

// Two spectators take one spectator slot in turn: the first watches and leaves, the second is
// seated once the first fell silent, joins late from the host's snapshot and sees the players'
// state; a third, while the second is live, is refused the slot.
TEST(MatchKinds, SpectatorsTakeASlotInTurnAndSeeThePlayersState) {
    HostConfig config;
    config.kind = MatchKind::e_rollbackRelay;
    config.match.playerCount = 2;
    config.match.inputBytes = replay::SceneInput::kBytes;
    config.match.disconnectMicros = 600'000;  // a silent spectator's slot is free after 0.6 s
    config.spectatorsPerMatch = 1;
    // Peer 0 hosts the spectator: its snapshot bursts need more than a player's default budget.
    config.peerBytesPerSecond = 1'000'000;
    Host h(std::move(config));
    std::vector<std::unique_ptr<RollbackClient>> peers;
    for (uint32_t slot = 0; slot < 2; ++slot)
        peers.push_back(std::make_unique<RollbackClient>(
            h.port, 12, slot, 2, Mint(12, static_cast<uint8_t>(slot), 120 + slot), 800 + slot, 1));
    std::unique_ptr<Watcher> first = std::make_unique<Watcher>(h.port, 12, 2, 3, Mint(12, 2, 130));
    std::unique_ptr<Watcher> second, third;
    // The players step at about 250 frames a second; everyone else as fast as the loop turns.
    const auto start = std::chrono::steady_clock::now();
    int32_t ticks = 0;
    bool firstLeft = false;
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
        const auto elapsed = std::chrono::steady_clock::now() - start;
        h.host->Update();
        if (elapsed >= std::chrono::milliseconds(4) * ticks) {
            for (auto& p : peers) p->Step(1 << 30);
            ++ticks;
        } else {
            for (auto& p : peers) p->peer->Poll();
        }
        if (first) first->Step();
        if (second) second->Step();
        if (third) third->Step();
        if (!firstLeft && first->frames >= 100) {
            // The first spectator leaves (its machine goes quiet); the second asks at once.
            firstLeft = true;
            first.reset();
            second = std::make_unique<Watcher>(h.port, 12, 2, 3, Mint(12, 2, 131));
        }
        if (second && !third && second->frames > 0)
            third = std::make_unique<Watcher>(h.port, 12, 2, 3, Mint(12, 2, 132));
        if (second && second->hashes.size() >= 3) break;
        std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    ASSERT_TRUE(firstLeft);
    ASSERT_TRUE(second);
    ASSERT_GE(second->hashes.size(), 3u);
    EXPECT_EQ(third->frames, 0);
    EXPECT_GT(Dropped(*h.host, Drop::e_slotTaken), 0u);
    // The second spectator's state equals the players' at every frame both hashed.
    size_t compared = 0;
    for (const auto& p : peers)
        for (const auto& [f, hash] : p->session->FinalHashes()) {
            const auto it = second->hashes.find(f);
            if (it == second->hashes.end()) continue;
            EXPECT_EQ(it->second, hash) << "frame " << f;
            ++compared;
        }
    EXPECT_GT(compared, 0u);
}

// A spectator's socket closes and its port goes to the next spectator, of another slot (a
// client host hands freed ports out again): the newcomer's fresh token takes the address over
// and its join is seated in its own slot; the departed spectator's token does not take it back.
TEST(MatchKinds, ANewClientOnADepartedSpectatorsAddressJoinsItsOwnSlot) {
    HostConfig config;
    config.kind = MatchKind::e_rollbackRelay;
    config.match.playerCount = 2;
    config.spectatorsPerMatch = 2;
    Host h(std::move(config));
    std::string error;
    auto udp = net::UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_TRUE(udp) << error;
    const net::PeerId server = udp->AddPeer("127.0.0.1", h.port, &error);
    const auto join = [&](const admission::TokenBytes& token, uint8_t slot) {
        std::vector<uint8_t> frame, out;
        net::WriteRelayFrame(frame, net::RelayKind::e_join, 14, slot);
        net::admission::WriteEnvelope(out, token, frame);
        EXPECT_TRUE(udp->Send(server, out));
    };
    const auto welcomed = [&] {  // the slots the relay welcomes us to over the next 50 ms
        std::vector<int> slots;
        for (int i = 0; i < 50; ++i) {
            h.host->Update();
            std::vector<net::Datagram> got;
            udp->Poll(got);
            for (const net::Datagram& d : got) {
                const auto f = net::ParseRelayFrame(d.bytes);
                if (f && f->kind == net::RelayKind::e_welcome) slots.push_back(f->slot);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        return slots;
    };
    join(Mint(14, 2, 140), 2);
    EXPECT_EQ(welcomed(), std::vector<int>{2});
    join(Mint(14, 3, 141), 3);  // the next spectator, on the same address
    EXPECT_EQ(welcomed(), std::vector<int>{3});
    EXPECT_EQ(h.host->Stats().rebound, 1u);
    EXPECT_EQ(Dropped(*h.host, Drop::e_wrongSlot), 0u);
    EXPECT_EQ(Dropped(*h.host, Drop::e_strayEnvelope), 0u);
    join(Mint(14, 2, 140), 2);  // a late datagram of the departed one
    EXPECT_TRUE(welcomed().empty());
    EXPECT_EQ(Dropped(*h.host, Drop::e_strayEnvelope), 1u);
    EXPECT_EQ(h.host->Stats().rebound, 1u);
    EXPECT_EQ(h.host->PlayerCount(), 1u);
}

TEST(MatchKinds, AnAdmittedClientOverItsBandwidthIsCutAndCounted) {
    HostConfig config;
    config.match.playerCount = 2;
    config.peerBytesPerSecond = 2000;  // one second's worth at once: 2000 bytes
    Host h(std::move(config));
    std::vector<std::unique_ptr<TestClient>> clients;
    clients.push_back(std::make_unique<TestClient>(h.port, Mint(4, 0, 40), 1, 10));
    testing::Pump([&] { h.host->Update(); }, clients, [&] { return h.host->PlayerCount() == 1; },
                  std::chrono::seconds(5));
    ASSERT_EQ(h.host->PlayerCount(), 1u);
    // 100 datagrams of 200 bytes at once from the admitted client's own address: about ten fit
    // in its budget, the rest are dropped unread.
    const std::vector<uint8_t> junk(200, 0x5A);
    for (int i = 0; i < 100; ++i) clients[0]->udp->Send(clients[0]->server, junk);
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(500)) {
        h.host->Update();
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    EXPECT_GE(Dropped(*h.host, Drop::e_peerBandwidth), 80u);
    EXPECT_LE(Dropped(*h.host, Drop::e_peerBandwidth), 95u);
}

// A relay member that only joins its slot: enough to be admitted and to send from its address.
struct RelayMember {
    std::unique_ptr<net::UdpTransport> udp;
    net::PeerId server = net::kNoPeer;
    std::unique_ptr<net::admission::AdmissionTransport> admission;
    std::unique_ptr<net::RelayedTransport> relayed;

    RelayMember(uint16_t port, uint32_t match, uint8_t slot, uint32_t slots, uint64_t nonce) {
        std::string error;
        udp = net::UdpTransport::Open("127.0.0.1", 0, &error);
        EXPECT_TRUE(udp) << error;
        server = udp->AddPeer("127.0.0.1", port, &error);
        admission = std::make_unique<net::admission::AdmissionTransport>(*udp, server, Mint(match, slot, nonce));
        relayed = std::make_unique<net::RelayedTransport>(
            *admission, net::RelayedTransportConfig{server, match, slot, slots, 0, 20000});
    }
    void Poll() {
        std::vector<net::Datagram> sink;
        relayed->Poll(sink);
    }
};

TEST(MatchKinds, ARollbackRelayBudgetIsPerStreamTheClientSends) {
    HostConfig config;
    config.kind = MatchKind::e_rollbackRelay;
    config.match.playerCount = 3;
    config.spectatorsPerMatch = 3;
    config.peerBytesPerSecond = 2000;  // per stream
    Host h(std::move(config));
    // Slot 0 sends to 2 players and hosts 3 spectator slots: 5 x 2,000 B/s. Slot 1 sends to 2
    // players: 4,000 B/s. Slot 3, a spectator, answers its host only: 2,000 B/s.
    RelayMember host(h.port, 5, 0, 6, 50), player(h.port, 5, 1, 6, 51), spectator(h.port, 5, 3, 6, 53);
    const auto start = std::chrono::steady_clock::now();
    while (h.host->PlayerCount() < 3 && std::chrono::steady_clock::now() - start < std::chrono::seconds(5)) {
        host.Poll();
        player.Poll();
        spectator.Poll();
        h.host->Update();
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    ASSERT_EQ(h.host->PlayerCount(), 3u);
    // 30 datagrams of 200 bytes at once from one member (its budget allows one second's worth
    // at once); returns how many the server dropped.
    const std::vector<uint8_t> burst(200, 0x5A);
    const auto blast = [&](RelayMember& m) {
        const uint64_t before = Dropped(*h.host, Drop::e_peerBandwidth);
        for (int i = 0; i < 30; ++i) m.udp->Send(m.server, burst);
        const auto begin = std::chrono::steady_clock::now();
        while (std::chrono::steady_clock::now() - begin < std::chrono::milliseconds(300)) {
            h.host->Update();
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
        return Dropped(*h.host, Drop::e_peerBandwidth) - before;
    };
    EXPECT_EQ(blast(host), 0u);                  // 6,000 bytes of 10,000
    const uint64_t playerDrops = blast(player);  // 6,000 of 4,000: about 10 of 30 dropped
    EXPECT_GE(playerDrops, 5u);                  // the budget refills while a slow machine reads the burst
    EXPECT_LE(playerDrops, 12u);
    const uint64_t spectatorDrops = blast(spectator);  // 6,000 of 2,000: about 20 dropped
    EXPECT_GE(spectatorDrops, 14u);
    EXPECT_GT(spectatorDrops, playerDrops);
}

TEST(MatchKinds, TheSpectatorsHostBudgetCanBeSetApart) {
    HostConfig config;
    config.kind = MatchKind::e_rollbackRelay;
    config.match.playerCount = 2;
    config.spectatorsPerMatch = 3;
    config.peerBytesPerSecond = 2000;
    config.spectatorHostBytesPerSecond = 2000;  // the host no richer than a player
    Host h(std::move(config));
    RelayMember host(h.port, 6, 0, 5, 60);
    const auto start = std::chrono::steady_clock::now();
    while (h.host->PlayerCount() < 1 && std::chrono::steady_clock::now() - start < std::chrono::seconds(5)) {
        host.Poll();
        h.host->Update();
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    ASSERT_EQ(h.host->PlayerCount(), 1u);
    const std::vector<uint8_t> burst(200, 0x5A);
    for (int i = 0; i < 30; ++i) host.udp->Send(host.server, burst);
    const auto begin = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - begin < std::chrono::milliseconds(300)) {
        h.host->Update();
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    EXPECT_GE(Dropped(*h.host, Drop::e_peerBandwidth), 20u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::server
