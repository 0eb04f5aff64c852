// RollbackMatch: the builder refuses each bad setting by name; two peers built with it play to
// frame N over SimNet (and over loopback UDP), agree on the final hash and both leave cleanly.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackMatch.h"
#include "lockbox/net/SimNet.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

WorldStepSettings StepOf(const replay::SceneGame& game) {
    const auto& info = game.info();
    return WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                             static_cast<uint32_t>(info.positionIterations)};
}

/// A scripted input as a pure function of (player, frame): an impulse on some body every
/// 7th frame, a box every 40th.
void Script(uint32_t player, int32_t frame, std::span<uint8_t> out) {
    replay::SceneInput in;
    const uint32_t mix = static_cast<uint32_t>(frame) * 2654435761u ^ (player + 1) * 40503u;
    if (frame % 7 == static_cast<int32_t>(player)) {
        in.action = replay::e_actImpulse;
        in.pick = static_cast<uint8_t>(mix >> 8);
        in.a = static_cast<int16_t>(static_cast<int32_t>(mix % 4097) - 2048);
        in.b = static_cast<int16_t>(mix % 3001);
    } else if (frame % 40 == 11) {
        in.action = replay::e_actSpawnBox;
        in.a = static_cast<int16_t>(static_cast<int32_t>(mix % 641) - 320);
        in.b = 960;
    }
    in.Encode(out.data());
}

class MatchBuilder : public ::testing::Test {
protected:
    MatchBuilder() : game("vertical_stack"), net(1), end(net.AddEndpoint()), other(net.AddEndpoint()) {}
    /// A valid two-player configuration to spoil one setting at a time.
    RollbackMatchBuilder Good() {
        RollbackMatchBuilder b;
        b.Players(2)
            .LocalPlayer(0)
            .RemotePlayer(1, other.Index())
            .InputBytes(8)
            .UseTransport(end)
            .World(game.world(), game, StepOf(game));
        return b;
    }
    static void ExpectRefused(const RollbackMatchBuilder& b, MatchSetting setting) {
        const RollbackMatchBuild built = b.Build();
        EXPECT_EQ(built.match, nullptr);
        EXPECT_EQ(built.error.setting, setting) << built.error.message;
        EXPECT_EQ(built.error.message.rfind(MatchSettingName(setting), 0), 0u) << built.error.message;
    }
    replay::SceneGame game;
    SimNet net;
    SimEndpoint& end;
    SimEndpoint& other;
};

TEST_F(MatchBuilder, GoodConfigurationBuilds) {
    const RollbackMatchBuild built = Good().Build();
    ASSERT_NE(built.match, nullptr) << built.error.message;
    EXPECT_TRUE(built.error.ok());
    EXPECT_EQ(built.match->Phase(), MatchPhase::e_synchronizing);
    EXPECT_EQ(built.match->TickMicros(), 16666u);
    EXPECT_EQ(&built.match->Net(), &end);
    EXPECT_EQ(built.match->Session().Config().inputDelay, 2u);
}

TEST_F(MatchBuilder, EachBadSettingIsNamed) {
    using S = MatchSetting;
    ExpectRefused(Good().Players(0), S::e_players);
    ExpectRefused(Good().Players(kRollbackMaxPlayers + 1), S::e_players);
    {
        RollbackMatchBuilder b;
        b.Players(2).RemotePlayer(1, other.Index()).UseTransport(end).World(game.world(), game, StepOf(game));
        ExpectRefused(b, S::e_localPlayers);  // none
    }
    ExpectRefused(Good().LocalPlayer(5), S::e_localPlayers);
    ExpectRefused(Good().LocalPlayer(0), S::e_localPlayers);        // twice
    ExpectRefused(Good().RemotePlayer(0, 3u), S::e_remotePlayers);  // local already
    ExpectRefused(Good().RemotePlayer(1, 3u), S::e_remotePlayers);  // twice
    ExpectRefused(Good().RemotePlayer(7, 3u), S::e_remotePlayers);  // past the count
    ExpectRefused(Good().Players(3), S::e_remotePlayers);           // player 2 unassigned
    ExpectRefused(Good().InputBytes(0), S::e_inputBytes);
    ExpectRefused(Good().InputBytes(kRollbackMaxInputBytes + 1), S::e_inputBytes);
    ExpectRefused(Good().InputDelay(kRollbackMaxInputDelay + 1), S::e_inputDelay);
    ExpectRefused(Good().PredictionWindow(0), S::e_predictionWindow);
    ExpectRefused(Good().PredictionWindow(kRollbackMaxWindow + 1), S::e_predictionWindow);
    ExpectRefused(Good().StartTimeoutMicros(0), S::e_startTimeout);
    ExpectRefused(Good().DisconnectTimeoutMicros(1), S::e_disconnectTimeout);
    ExpectRefused(Good().World(game.world(), game, WorldStepSettings{0, 8, 3}), S::e_world);
    {
        RollbackMatchBuilder b;
        b.Players(2).LocalPlayer(0).RemotePlayer(1, other.Index()).UseTransport(end);
        ExpectRefused(b, S::e_world);  // none
    }
    {
        RollbackMatchBuilder b;
        b.Players(2).LocalPlayer(0).RemotePlayer(1, other.Index()).World(game.world(), game, StepOf(game));
        ExpectRefused(b, S::e_transport);  // none
    }
    ExpectRefused(Good().UdpPort(0), S::e_transport);  // both
    {
        RollbackMatchBuilder b;
        b.Players(2)
            .LocalPlayer(0)
            .RemotePlayer(1, "127.0.0.1", 9)
            .UseTransport(end)
            .World(game.world(), game, StepOf(game));
        ExpectRefused(b, S::e_transport);  // an address on SimNet
    }
    LatencyProfile tooLossy;
    tooLossy.lossPermille = 1001;
    ExpectRefused(Good().Latency(tooLossy, 1), S::e_latency);
    {
        RollbackMatchBuilder b;
        b.Players(2).LocalPlayer(0).RemotePlayer(1, "127.0.0.1", 0).UdpPort(0).World(game.world(), game, StepOf(game));
        ExpectRefused(b, S::e_address);  // port 0
    }
    {
        RollbackMatchBuilder b;
        b.Players(2)
            .LocalPlayer(0)
            .RemotePlayer(1, "not-an-address", 7000)
            .UdpPort(0)
            .World(game.world(), game, StepOf(game));
        ExpectRefused(b, S::e_address);
    }
    {
        RollbackMatchBuilder b;
        b.Players(2)
            .LocalPlayer(0)
            .RemotePlayer(1, "127.0.0.1", 7000)
            .UdpPort(0, "203.0.113.7")
            .World(game.world(), game, StepOf(game));
        ExpectRefused(b, S::e_port);  // an address this machine does not have
    }
}

TEST_F(MatchBuilder, EndAtRefusesFramesNoPeerHashes) {
    RollbackMatchBuild built = Good().DesyncInterval(10).Build();
    ASSERT_NE(built.match, nullptr);
    EXPECT_FALSE(built.match->EndAt(95, 1000000));
    EXPECT_FALSE(built.match->EndAt(-10, 1000000));
    EXPECT_TRUE(built.match->EndAt(100, 1000000));
    RollbackMatchBuild off = Good().DesyncInterval(0).Build();
    ASSERT_NE(off.match, nullptr);
    EXPECT_FALSE(off.match->EndAt(100, 1000000));
}

/// Two (or three) peers on one SimNet, built with the builder, ticked on the virtual clock.
struct SimMatch {
    explicit SimMatch(uint32_t players, uint64_t seed, LinkProfile link) : net(seed) {
        net.SetAllLinks(link);
        for (uint32_t i = 0; i < players; ++i) ends.push_back(&net.AddEndpoint());
        for (uint32_t i = 0; i < players; ++i) games.push_back(std::make_unique<replay::SceneGame>("vertical_stack"));
        for (uint32_t i = 0; i < players; ++i) {
            RollbackMatchBuilder b;
            b.Players(players).LocalPlayer(i).InputBytes(replay::SceneInput::kBytes).InputDelay(1).DesyncInterval(10);
            for (uint32_t j = 0; j < players; ++j)
                if (j != i) b.RemotePlayer(j, ends[j]->Index());
            b.UseTransport(*ends[i]).World(games[i]->world(), *games[i], StepOf(*games[i]));
            RollbackMatchBuild built = b.Build();
            EXPECT_NE(built.match, nullptr) << built.error.message;
            matches.push_back(std::move(built.match));
        }
    }
    /// Ticks every match until all are over or `maxTicks` passed.
    void Run(int32_t maxTicks) {
        for (int32_t t = 0; t < maxTicks; ++t) {
            bool over = true;
            for (auto& m : matches) {
                m->Tick(Script);
                over = over && m->End().ended;
            }
            if (over) return;
            net.Advance(16666);
        }
    }
    SimNet net;
    std::vector<SimEndpoint*> ends;
    std::vector<std::unique_ptr<replay::SceneGame>> games;
    std::vector<std::unique_ptr<RollbackMatch>> matches;
};

TEST(MatchEnd, TwoPeersOnSimNetEndAtFrameNAndAgree) {
    LinkProfile link;
    link.latencyMicros = 30000;
    link.jitterMicros = 10000;
    link.lossPpm = 50000;
    SimMatch sim(2, 11, link);
    for (auto& m : sim.matches) ASSERT_TRUE(m->EndAt(180, 5000000));
    sim.Run(2000);
    for (size_t i = 0; i < 2; ++i) {
        const RollbackMatchEnd& e = sim.matches[i]->End();
        SCOPED_TRACE("peer " + std::to_string(i));
        EXPECT_TRUE(e.ended);
        EXPECT_TRUE(e.finished) << e.failure;
        EXPECT_FALSE(e.timedOut);
        EXPECT_TRUE(e.Agreed());
        EXPECT_EQ(e.frame, 180);
        EXPECT_EQ(sim.matches[i]->Session().CurrentFrame(), 180);
        EXPECT_EQ(sim.matches[i]->Phase(), MatchPhase::e_ended);
        ASSERT_EQ(e.remotes.size(), 1u);
    }
    EXPECT_EQ(sim.matches[0]->End().hash, sim.matches[1]->End().hash);
    // Both left by RbDisconnect: at least one heard the other's hash before it left, and the
    // other either heard it too or saw it leave; nobody timed out.
    const bool bothHashed = sim.matches[0]->End().remotes[0].hashed && sim.matches[1]->End().remotes[0].hashed;
    const bool oneLeftFirst = sim.matches[0]->End().remotes[0].left || sim.matches[1]->End().remotes[0].left;
    EXPECT_TRUE(bothHashed || oneLeftFirst);
    EXPECT_GT(sim.matches[0]->Session().Stats().rollbacks + sim.matches[1]->Session().Stats().rollbacks, 0u);
}

TEST(MatchEnd, SameScriptSameFinalHashWhateverTheNetwork) {
    // Inputs are a function of the frame, so the final hash depends on the script only.
    LinkProfile clean;
    SimMatch a(2, 1, clean);
    LinkProfile rough;
    rough.latencyMicros = 60000;
    rough.jitterMicros = 20000;
    rough.lossPpm = 100000;
    SimMatch b(2, 2, rough);
    for (SimMatch* s : {&a, &b}) {
        for (auto& m : s->matches) ASSERT_TRUE(m->EndAt(120, 5000000));
        s->Run(2000);
        for (auto& m : s->matches) ASSERT_TRUE(m->End().finished) << m->End().failure;
    }
    EXPECT_EQ(a.matches[0]->End().hash, b.matches[0]->End().hash);
    EXPECT_EQ(a.matches[1]->End().hash, b.matches[1]->End().hash);
}

TEST(MatchEnd, ThreePeersEndTogether) {
    LinkProfile link;
    link.latencyMicros = 20000;
    link.jitterMicros = 5000;
    link.lossPpm = 20000;
    SimMatch sim(3, 5, link);
    for (auto& m : sim.matches) ASSERT_TRUE(m->EndAt(120, 5000000));
    sim.Run(2000);
    for (auto& m : sim.matches) {
        EXPECT_TRUE(m->End().finished) << m->End().failure;
        EXPECT_TRUE(m->End().Agreed());
        EXPECT_EQ(m->End().hash, sim.matches[0]->End().hash);
    }
}

TEST(MatchEnd, PeerThatNeverAppearsIsNamed) {
    replay::SceneGame game("vertical_stack");
    RollbackMatchBuilder b;
    b.Players(2)
        .LocalPlayer(0)
        .RemotePlayer(1, "127.0.0.1", 9)
        .UdpPort(0)
        .StartTimeoutMicros(300000)
        .World(game.world(), game, StepOf(game));
    RollbackMatchBuild built = b.Build();
    ASSERT_NE(built.match, nullptr) << built.error.message;
    const RollbackMatchEnd e = built.match->PlayTo(60, Script, 1000000);
    EXPECT_TRUE(e.failed);
    EXPECT_FALSE(e.finished);
    EXPECT_NE(e.failure.find("127.0.0.1:9"), std::string::npos) << e.failure;
    EXPECT_EQ(built.match->Phase(), MatchPhase::e_failed);
    EXPECT_EQ(built.match->Session().CurrentFrame(), 0);
}

// Two peers on 127.0.0.1 sockets, each on its own thread with PlayTo, the second started
// 300 ms after the first; 40 ms of LatencyTransport each way. Generous bounds: the run takes
// about 3 s of real time.
TEST(MatchEnd, TwoPeersOnLoopbackUdpEndAtFrameNAndAgree) {
    constexpr int32_t kFrames = 120;
    replay::SceneGame games[2] = {replay::SceneGame("vertical_stack"), replay::SceneGame("vertical_stack")};
    std::string error;
    // Ports: open each side's socket on an ephemeral port first, then point the other at it.
    auto probe0 = UdpTransport::Open("127.0.0.1", 0, &error);
    auto probe1 = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_TRUE(probe0 && probe1) << error;
    const uint16_t ports[2] = {probe0->LocalPort(), probe1->LocalPort()};
    probe0.reset();
    probe1.reset();
    std::unique_ptr<RollbackMatch> matches[2];
    LatencyProfile cable;
    cable.latencyMicros = 40000;
    for (uint32_t i = 0; i < 2; ++i) {
        RollbackMatchBuilder b;
        b.Players(2)
            .LocalPlayer(i)
            .RemotePlayer(1 - i, "127.0.0.1", ports[1 - i])
            .InputBytes(replay::SceneInput::kBytes)
            .UdpPort(ports[i])
            .Latency(cable, 7 + i)
            .World(games[i].world(), games[i], StepOf(games[i]));
        RollbackMatchBuild built = b.Build();
        ASSERT_NE(built.match, nullptr) << built.error.message;
        matches[i] = std::move(built.match);
    }
    RollbackMatchEnd ends[2];
    std::thread first([&] { ends[0] = matches[0]->PlayTo(kFrames, Script, 10000000); });
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    std::thread second([&] { ends[1] = matches[1]->PlayTo(kFrames, Script, 10000000); });
    first.join();
    second.join();
    for (int i = 0; i < 2; ++i) {
        SCOPED_TRACE("peer " + std::to_string(i));
        EXPECT_TRUE(ends[i].finished) << ends[i].failure;
        EXPECT_FALSE(ends[i].timedOut);
        EXPECT_TRUE(ends[i].Agreed());
        EXPECT_EQ(ends[i].frame, kFrames);
    }
    EXPECT_EQ(ends[0].hash, ends[1].hash);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
