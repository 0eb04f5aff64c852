// End to end over real sockets on loopback: a LockstepServer and two
// LockstepClients in one thread, over UdpTransport (127.0.0.1 and ::1) and EnetTransport
// (127.0.0.1). Bounded by frames and wall seconds; the run stops by itself.

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/EnetTransport.h"
#include "lockbox/net/LockstepClient.h"
#include "lockbox/net/LockstepServer.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

constexpr int32_t kFrames = 240;
constexpr uint32_t kTickRate = 240;  // a fast tick keeps the wall time short
constexpr auto kWallLimit = std::chrono::seconds(15);

struct Side {
    std::unique_ptr<Transport> transport;
    PeerId server = kNoPeer;
    std::unique_ptr<replay::SceneGame> game;
    std::unique_ptr<replay::ScriptedInputs> inputs;
    std::unique_ptr<LockstepClient> client;
    uint64_t hashAtEnd = 0;
};

// Runs the match until both clients stepped kFrames frames or the wall limit passes.
void Play(Transport& serverTransport, std::vector<Side>& sides) {
    ServerConfig sc;
    sc.playerCount = static_cast<uint32_t>(sides.size());
    sc.tickRate = kTickRate;
    sc.hashInterval = 20;
    LockstepServer server(serverTransport, sc);
    for (size_t i = 0; i < sides.size(); ++i) {
        Side& s = sides[i];
        s.game = std::make_unique<replay::SceneGame>("vertical_stack");
        s.inputs = std::make_unique<replay::ScriptedInputs>(500 + i, 1);
        s.client = std::make_unique<LockstepClient>(*s.transport, s.server, ClientConfig{}, s.game->world(), *s.game);
        s.client->SetConfirmedFrameHook([&s](int32_t f, std::span<const uint8_t>, uint64_t, const b2World&) {
            if (f == kFrames - 1) s.hashAtEnd = s.client->LastHash();
        });
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<uint8_t> input;
    for (uint64_t iteration = 0; iteration < 2'000'000; ++iteration) {
        bool done = true;
        for (const Side& s : sides) done = done && s.client->Frame() >= kFrames;
        if (done || std::chrono::steady_clock::now() - start > kWallLimit) break;
        server.Update();
        for (Side& s : sides) {
            s.client->Update();
            while (s.client->WantsInput()) {
                s.inputs->Next(input);
                if (!s.client->SubmitLocalInput(input)) break;
            }
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    for (const ServerEvent& e : server.TakeEvents()) EXPECT_NE(e.kind, ServerEvent::Kind::e_desync);
    for (size_t i = 0; i < sides.size(); ++i) {
        EXPECT_GE(sides[i].client->Frame(), kFrames)
            << "client " << i << " state " << static_cast<int>(sides[i].client->State());
        EXPECT_NE(sides[i].hashAtEnd, 0u);
        EXPECT_EQ(sides[i].hashAtEnd, sides[0].hashAtEnd) << "client " << i;
    }
}

void PlayUdp(const std::string& host) {
    std::string error;
    auto serverT = UdpTransport::Open(host, 0, &error);
    if (!serverT && host == "::1") GTEST_SKIP() << "no IPv6 loopback: " << error;
    ASSERT_TRUE(serverT) << error;
    std::vector<Side> sides(2);
    for (Side& s : sides) {
        auto t = UdpTransport::Open(host, 0, &error);
        ASSERT_TRUE(t) << error;
        s.server = t->AddPeer(host, serverT->LocalPort(), &error);
        ASSERT_NE(s.server, kNoPeer) << error;
        s.transport = std::move(t);
    }
    Play(*serverT, sides);
}

TEST(LockstepLoopback, UdpIpv4) { PlayUdp("127.0.0.1"); }
TEST(LockstepLoopback, UdpIpv6) { PlayUdp("::1"); }

TEST(LockstepLoopback, Enet) {
    std::string error;
    auto serverT = EnetTransport::Listen(0, 8, &error);
    ASSERT_TRUE(serverT) << error;
    std::vector<Side> sides(2);
    for (Side& s : sides) {
        auto t = EnetTransport::Client(&error);
        ASSERT_TRUE(t) << error;
        s.server = t->Connect("127.0.0.1", serverT->LocalPort(), &error);
        ASSERT_NE(s.server, kNoPeer) << error;
        s.transport = std::move(t);
    }
    Play(*serverT, sides);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
