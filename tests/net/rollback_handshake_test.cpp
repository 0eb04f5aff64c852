// The compatibility check of rollback protocol 4 (docs/rollback.md, "Compatibility"): a peer
// or spectator of another protocol version, match id, engine determinism version or session
// shape is named once with the reason, instead of playing on to a desync or a silent timeout.
// Two integer-state sessions (RollbackMixGame.h) on a zero-latency SimNet.

#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "ForwardingTransport.h"
#include "RollbackMixGame.h"
#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/RollbackSpectator.h"
#include "lockbox/net/SimNet.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

constexpr uint64_t kTick = 16666;
constexpr uint32_t kInputBytes = 2;

// A transport that counts, per tick, the datagrams it sent that carry an RbHello.
class HelloCounter : public ForwardingTransport {
public:
    using ForwardingTransport::ForwardingTransport;
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override {
        RollbackHeader h;
        std::vector<RollbackMessage> m;
        DecodeRollbackDatagram(bytes, RollbackShape{2, kInputBytes}, h, m);
        for (const RollbackMessage& x : m)
            if (std::holds_alternative<RbHello>(x)) lastHelloTick = tick;
        if (!m.empty() && std::holds_alternative<RbHello>(m.front())) ++hellos;
        return ForwardingTransport::Send(peer, bytes, delivery);
    }
    int64_t tick = 0;
    int64_t lastHelloTick = -1;
    uint64_t hellos = 0;  ///< datagrams whose first message is a hello
};

struct Side {
    std::unique_ptr<RollbackSession> session;
    std::unique_ptr<HelloCounter> link;
    std::unique_ptr<RollbackPeer> peer;
    MixGame game;
    std::vector<RollbackEvent> events;

    int Count(RollbackEvent::Kind kind) const {
        int n = 0;
        for (const RollbackEvent& e : events) n += e.kind == kind ? 1 : 0;
        return n;
    }
};

// Two peers (player 0 on A, player 1 on B) and optionally a spectator listed at A. `tweakB`
// and `tweakSpectator` change what the second machine runs with.
struct Match {
    SimNet net{7};
    SimEndpoint* ends[3] = {};
    Side sides[2];
    std::unique_ptr<RollbackSpectator> spectator;
    int32_t spectatorFrames = 0;

    Match(uint32_t inputBytesB, RollbackPeerConfig configB, bool withSpectator,
          RollbackSpectatorConfig spectatorConfig = {}) {
        for (SimEndpoint*& e : ends) e = &net.AddEndpoint();
        for (uint32_t i = 0; i < 2; ++i) {
            Side& s = sides[i];
            const uint32_t bytes = i == 0 ? kInputBytes : inputBytesB;
            s.session = RollbackSessionBuilder()
                            .Players(2)
                            .InputBytes(bytes)
                            .LocalPlayer(i)
                            .PredictionWindow(8)
                            .DesyncInterval(1)
                            .Build();
            s.link = std::make_unique<HelloCounter>(*ends[i]);
            RollbackPeerConfig c = i == 0 ? RollbackPeerConfig{} : configB;
            c.startTimeoutMicros = 3'000'000;
            c.remotes = {RollbackRemote{ends[1 - i]->Index(), {1 - i}}};
            if (i == 0 && withSpectator) c.spectators = {ends[2]->Index()};
            s.peer = std::make_unique<RollbackPeer>(*s.session, *s.link, c);
        }
        if (withSpectator) {
            spectatorConfig.players = 2;
            spectatorConfig.inputBytes = kInputBytes;
            spectatorConfig.host = ends[0]->Index();
            spectator = std::make_unique<RollbackSpectator>(*ends[2], spectatorConfig);
        }
    }

    void Run(int64_t ticks) {
        for (int64_t t = 0; t < ticks; ++t) {
            net.Advance(kTick);
            for (uint32_t i = 0; i < 2; ++i) {
                Side& s = sides[i];
                s.link->tick = t;
                s.peer->Poll();
                const uint32_t bytes = s.session->Config().inputBytes;
                s.session->AddLocalInput(i, std::vector<uint8_t>(bytes, static_cast<uint8_t>(t % 7 + i)));
                s.game.Run(*s.session, s.session->AdvanceFrame());
                for (const RollbackEvent& e : s.session->TakeEvents()) s.events.push_back(e);
                s.peer->Flush();
            }
            if (spectator) {
                spectator->Poll();
                int32_t frame = 0;
                std::vector<uint8_t> inputs;
                while (spectator->Next(frame, inputs)) ++spectatorFrames;
                spectator->Flush();
            }
        }
    }
};

// Both sides name the other once, with `why`, take none of its inputs, never start the
// match, and name it again when the start timeout expires (then leave).
void ExpectNamedAndNotStarted(Match& m, RollbackIncompatibility why) {
    m.Run(10);
    for (uint32_t i = 0; i < 2; ++i) {
        SCOPED_TRACE(::testing::Message() << "side " << i);
        const Side& s = m.sides[i];
        ASSERT_EQ(s.Count(RollbackEvent::Kind::e_incompatible), 1);
        for (const RollbackEvent& e : s.events)
            if (e.kind == RollbackEvent::Kind::e_incompatible) {
                EXPECT_EQ(e.player, 0u);  // the remote's config index
                EXPECT_EQ(e.incompatibility, why) << RollbackIncompatibilityName(e.incompatibility);
            }
        EXPECT_EQ(s.peer->RemoteIncompatibility(0), why);
        EXPECT_EQ(s.session->ReceivedFrame(1 - i), 0);  // nothing taken from it
        EXPECT_GT(s.peer->Stats().refused, 0u);
    }
    m.Run(200);  // past the 3 s start timeout the match sets
    for (uint32_t i = 0; i < 2; ++i) {
        const Side& s = m.sides[i];
        EXPECT_EQ(s.Count(RollbackEvent::Kind::e_incompatible), 1) << "named once";
        EXPECT_EQ(s.Count(RollbackEvent::Kind::e_startTimeout), 1);
        EXPECT_EQ(s.Count(RollbackEvent::Kind::e_running), 0);
        EXPECT_EQ(s.peer->State(), RollbackPeerState::e_startFailed);
        EXPECT_EQ(s.session->CurrentFrame(), 0);  // never ran on zero inputs
        EXPECT_EQ(s.Count(RollbackEvent::Kind::e_desync), 0);
    }
}

TEST(RollbackHandshake, CompatiblePeersStopTheHelloOnceAcked) {
    Match m(kInputBytes, RollbackPeerConfig{}, false);
    m.Run(120);
    for (uint32_t i = 0; i < 2; ++i) {
        const Side& s = m.sides[i];
        EXPECT_EQ(s.Count(RollbackEvent::Kind::e_incompatible), 0);
        EXPECT_EQ(s.peer->RemoteIncompatibility(0), RollbackIncompatibility::e_none);
        EXPECT_GE(s.session->ConfirmedFrame(), 100);
        EXPECT_GE(s.link->hellos, 1u);
        // Zero latency: the remote's view acks our first input within a few ticks.
        EXPECT_GE(s.link->lastHelloTick, 0);
        EXPECT_LE(s.link->lastHelloTick, 5);
    }
    // A confirmed frame's state is the same on both.
    EXPECT_EQ(m.sides[0].game.saved.at(100), m.sides[1].game.saved.at(100));
}

TEST(RollbackHandshake, OtherDeterminismVersionIsNamed) {
    RollbackPeerConfig b;
    b.determinismVersion = b2_determinismVersion + 1;  // an older or newer engine
    Match m(kInputBytes, b, false);
    ExpectNamedAndNotStarted(m, RollbackIncompatibility::e_determinismVersion);
}

TEST(RollbackHandshake, OtherMatchIdIsNamed) {
    RollbackPeerConfig b;
    b.matchId = 2;
    Match m(kInputBytes, b, false);
    ExpectNamedAndNotStarted(m, RollbackIncompatibility::e_matchId);
}

TEST(RollbackHandshake, OtherInputSizeIsNamed) {
    Match m(kInputBytes + 1, RollbackPeerConfig{}, false);
    ExpectNamedAndNotStarted(m, RollbackIncompatibility::e_sessionShape);
}

// A datagram of protocol 3 (before the hello existed), 6 (before the start phase: such a
// peer would start at once and cut us at frame 0) or 7 (before RbQuality's sequence byte)
// from a configured remote.
class RollbackHandshakeOlder : public ::testing::TestWithParam<uint8_t> {};
INSTANTIATE_TEST_SUITE_P(Versions, RollbackHandshakeOlder, ::testing::Values(uint8_t{3}, uint8_t{6}, uint8_t{7}));

TEST_P(RollbackHandshakeOlder, OlderProtocolIsNamed) {
    ASSERT_LT(GetParam(), kRollbackProtocolVersion);
    SimNet net(3);
    SimEndpoint& a = net.AddEndpoint();
    SimEndpoint& old = net.AddEndpoint();
    auto session = RollbackSessionBuilder().Players(2).InputBytes(kInputBytes).LocalPlayer(0).Build();
    RollbackPeerConfig c;
    c.remotes = {RollbackRemote{old.Index(), {1}}};
    RollbackPeer peer(*session, a, c);
    const std::vector<uint8_t> v3{0x52, 0x42, GetParam(), 1,
                                  0,    0,    0,          static_cast<uint8_t>(RollbackMessageType::e_keepAlive)};
    for (int i = 0; i < 3; ++i) {
        old.Send(a.Index(), v3);
        net.Advance(kTick);
        peer.Poll();
    }
    const std::vector<RollbackEvent> events = session->TakeEvents();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, RollbackEvent::Kind::e_incompatible);
    EXPECT_EQ(events[0].incompatibility, RollbackIncompatibility::e_protocolVersion);
    EXPECT_EQ(peer.Stats().refused, 3u);
}

TEST(RollbackHandshake, SpectatorOfAnotherEngineIsRefusedBothWays) {
    RollbackSpectatorConfig sc;
    sc.determinismVersion = b2_determinismVersion + 1;
    Match m(kInputBytes, RollbackPeerConfig{}, true, sc);
    m.Run(60);
    EXPECT_EQ(m.spectator->State(), SpectatorState::e_incompatible);
    EXPECT_EQ(m.spectator->Incompatibility(), RollbackIncompatibility::e_determinismVersion);
    EXPECT_EQ(m.spectatorFrames, 0);
    EXPECT_EQ(m.sides[0].peer->IncompatibleSpectators(), 1u);
    // The players are not disturbed.
    EXPECT_GE(m.sides[0].session->ConfirmedFrame(), 40);
    EXPECT_EQ(m.sides[0].Count(RollbackEvent::Kind::e_incompatible), 0);
}

TEST(RollbackHandshake, CompatibleSpectatorFollows) {
    Match m(kInputBytes, RollbackPeerConfig{}, true);
    m.Run(60);
    EXPECT_EQ(m.spectator->State(), SpectatorState::e_following);
    EXPECT_EQ(m.spectator->Incompatibility(), RollbackIncompatibility::e_none);
    EXPECT_GE(m.spectatorFrames, 40);
    EXPECT_EQ(m.sides[0].peer->IncompatibleSpectators(), 0u);
}

// ---- Wire -----------------------------------------------------------------------------

std::vector<uint8_t> Datagram1(const RollbackMessage& m, const RollbackShape& shape, uint32_t matchId = 1) {
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{kRollbackProtocolVersion, matchId});
    EXPECT_TRUE(w.Add(m, shape));
    const auto b = w.Bytes();
    return {b.begin(), b.end()};
}

TEST(RollbackHandshakeWire, HelloRoundTripsAndStopsAtAnotherShape) {
    const RollbackShape shape{2, kInputBytes};
    const RbHello hello{0xA1B2C3D4u, 2, kInputBytes};
    RollbackHeader h;
    std::vector<RollbackMessage> out;
    const auto bytes = Datagram1(hello, shape);
    ASSERT_EQ(DecodeRollbackDatagram(bytes, shape, h, out), DecodeError::e_ok);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(std::get<RbHello>(out[0]), hello);
    // Decodable without a shape (it is how a receiver learns the sender's).
    ASSERT_EQ(DecodeRollbackDatagram(bytes, RollbackShape{}, h, out), DecodeError::e_ok);
    // Another shape: decoding stops at the hello, which is all that is returned.
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{kRollbackProtocolVersion, 1});
    const RbHello other{7, 3, 4};
    ASSERT_TRUE(w.Add(other, RollbackShape{3, 4}));
    ASSERT_TRUE(w.Add(RbInputs{2, 0, std::vector<uint8_t>(4, 1)}, RollbackShape{3, 4}));
    const auto b = w.Bytes();
    ASSERT_EQ(DecodeRollbackDatagram(b, shape, h, out), DecodeError::e_incompatible);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(std::get<RbHello>(out[0]), other);
    EXPECT_EQ(FindIncompatibility(DecodeError::e_incompatible, h, out, 1, 7), RollbackIncompatibility::e_sessionShape);
    EXPECT_EQ(FindIncompatibility(DecodeError::e_incompatible, h, out, 1, 8),
              RollbackIncompatibility::e_determinismVersion);
    EXPECT_EQ(FindIncompatibility(DecodeError::e_incompatible, h, out, 2, 7), RollbackIncompatibility::e_matchId);
    EXPECT_EQ(FindIncompatibility(DecodeError::e_truncated, h, out, 1, 7), RollbackIncompatibility::e_none);
    EXPECT_EQ(FindIncompatibility(DecodeError::e_badVersion, h, out, 1, 7), RollbackIncompatibility::e_protocolVersion);
}

TEST(RollbackHandshakeWire, HelloOutOfRangeIsRefused) {
    const RollbackShape shape{2, kInputBytes};
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{kRollbackProtocolVersion, 1});
    EXPECT_FALSE(w.Add(RbHello{1, 0, kInputBytes}, shape));
    EXPECT_FALSE(w.Add(RbHello{1, kRollbackMaxPlayers + 1, kInputBytes}, shape));
    EXPECT_FALSE(w.Add(RbHello{1, 2, 0}, shape));
    EXPECT_FALSE(w.Add(RbHello{1, 2, kRollbackMaxInputBytes + 1}, shape));
    // Hand-made: players 0.
    std::vector<uint8_t> bad{0x52,
                             0x42,
                             kRollbackProtocolVersion,
                             1,
                             0,
                             0,
                             0,
                             static_cast<uint8_t>(RollbackMessageType::e_hello),
                             1,
                             0,
                             0,
                             0,
                             0,
                             2};
    RollbackHeader h;
    std::vector<RollbackMessage> out;
    EXPECT_EQ(DecodeRollbackDatagram(bad, shape, h, out), DecodeError::e_badValue);
    EXPECT_TRUE(out.empty());
    bad[12] = 2;
    bad[13] = 0;  // input bytes 0
    EXPECT_EQ(DecodeRollbackDatagram(bad, shape, h, out), DecodeError::e_badValue);
    bad.pop_back();  // truncated varint
    EXPECT_EQ(DecodeRollbackDatagram(bad, shape, h, out), DecodeError::e_truncated);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
