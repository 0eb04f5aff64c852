// Lockstep sessions under faults: a forced divergence gives exactly one
// desync event naming the frame (and none when the clients report no hashes), spoofed slots
// are refused, a fuzzed packet stream leaves the server running, a silent client is reported within the timeouts, and
// late joiners and reconnecting players reach hash agreement.

#include <random>

#include <gtest/gtest.h>

#include "LockstepHarness.h"

namespace lockbox::net::testing {
namespace LOCKBOX_TEST_FILE {

MatchSpec Spec(uint64_t seed, uint32_t clients) {
    MatchSpec s;
    s.seed = seed;
    s.clients = clients;
    s.rttMs = 40;
    s.jitterMs = 5;
    return s;
}

std::vector<uint8_t> Datagram(const Header& h, const std::vector<Message>& messages, const SessionShape& shape) {
    DatagramWriter w;
    w.Begin(h);
    for (const Message& m : messages) w.Add(m, shape);
    return {w.Bytes().begin(), w.Bytes().end()};
}

TEST(LockstepSession, ForcedDivergenceGivesOneDesyncAtThatFrame) {
    MatchSpec s = Spec(101, 3);
    s.hashInterval = 1;
    s.frames = 200;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    const int32_t kFrame = 97;
    m.player(1).nudge.nudgeFrame = kFrame;
    ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
    ASSERT_TRUE(m.RunUntil([&] { return m.CountServerEvents(ServerEvent::Kind::e_desync) > 0; }, 2'000));
    m.RunUntil([] { return false; }, 500);  // more reports arrive: still one event
    ASSERT_EQ(m.CountServerEvents(ServerEvent::Kind::e_desync), 1u);
    for (const ServerEvent& e : m.serverEvents()) {
        if (e.kind != ServerEvent::Kind::e_desync) continue;
        EXPECT_EQ(e.frame, kFrame);
        ASSERT_GE(e.hashes.size(), 2u);
        bool sawSlot1 = false;
        for (const SlotHash& h : e.hashes) sawSlot1 = sawSlot1 || h.slot == m.player(1).client->Slot();
        EXPECT_TRUE(sawSlot1 || e.hashes.size() < 3) << "the diverged slot's hash is listed when it arrived";
    }
    EXPECT_GT(m.server().Stats().desyncFrames, 1u);  // later frames differ too, counted only
    for (size_t i = 0; i < m.players(); ++i) {
        bool notified = false;
        for (const ClientEvent& e : m.player(i).events)
            notified = notified || (e.kind == ClientEvent::Kind::e_desync && e.frame == kFrame);
        EXPECT_TRUE(notified) << "client " << i;
    }
}

TEST(LockstepSession, DivergenceBetweenReportsNamesTheNextReportedFrame) {
    MatchSpec s = Spec(102, 2);
    s.hashInterval = 10;
    s.frames = 150;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    m.player(0).nudge.nudgeFrame = 43;
    ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
    m.RunUntil([&] { return m.CountServerEvents(ServerEvent::Kind::e_desync) > 0; }, 2'000);
    ASSERT_EQ(m.CountServerEvents(ServerEvent::Kind::e_desync), 1u);
    for (const ServerEvent& e : m.serverEvents()) {
        if (e.kind == ServerEvent::Kind::e_desync) {
            EXPECT_EQ(e.frame, 50);
        }
    }
}

TEST(LockstepSession, ClientsThatReportNoHashesAreNeverCompared) {
    MatchSpec s = Spec(109, 2);
    s.hashInterval = 10;
    s.frames = 150;
    SCOPED_TRACE(s.Describe());
    ClientConfig quiet;
    quiet.reportHashes = false;
    Match m(s, ServerConfig{}, quiet);
    m.player(1).nudge.nudgeFrame = 43;
    ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
    m.RunUntil([] { return false; }, 500);
    EXPECT_NE(m.player(0).client->LastHash(), m.player(1).client->LastHash()) << "the states diverged";
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_desync), 0u);
    EXPECT_EQ(m.server().Stats().desyncFrames, 0u);
}

TEST(LockstepSession, SpoofedSlotIsRejectedAndCounted) {
    MatchSpec s = Spec(103, 2);
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(60, 60'000));
    Player& liar = m.player(0);
    const int32_t victim = 1 - liar.client->Slot();
    const int32_t target = m.server().ConfirmedFrames() + 30;
    Header h;
    h.token = liar.client->Token();
    Inputs fake;
    fake.slot = static_cast<uint8_t>(victim);
    fake.firstFrame = target;
    fake.bytes.assign(8, 0xEE);
    liar.endpoint.Send(0, Datagram(h, {fake}, liar.client->Shape()));
    // A stranger (no Hello, no token) trying the same is refused as an unknown peer.
    SimEndpoint& stranger = m.net().AddEndpoint();
    stranger.Send(0, Datagram(Header{}, {fake}, liar.client->Shape()));
    ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
    EXPECT_EQ(m.server().Stats().spoofedInputs, 1u);
    EXPECT_GE(m.server().Stats().unknownPeer, 1u);
    ASSERT_EQ(m.CountServerEvents(ServerEvent::Kind::e_spoofedInput), 1u);
    for (const ServerEvent& e : m.serverEvents()) {
        if (e.kind != ServerEvent::Kind::e_spoofedInput) continue;
        EXPECT_EQ(e.peer, liar.endpoint.Index());
        EXPECT_EQ(e.claimedSlot, victim);
    }
    const std::span<const uint8_t> row = m.server().ConfirmedInputs(target);
    ASSERT_EQ(row.size(), 16u);
    EXPECT_NE(row[static_cast<size_t>(victim) * 8], 0xEE);  // the victim's own input was kept
    EXPECT_EQ(m.player(0).hashAtStop, m.player(1).hashAtStop);
}

TEST(LockstepSession, FuzzedPacketStreamLeavesTheServerRunning) {
    MatchSpec s = Spec(104, 2);
    s.lossPpm = 20'000;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    SimEndpoint& attacker = m.net().AddEndpoint();
    std::mt19937_64 rng(s.seed);
    const SessionShape shape{2, 8};
    uint64_t sent = 0;
    const bool done = m.RunUntil(
        [&] {
            // Every millisecond: random bytes, a truncated or mutated valid datagram, or a valid
            // datagram with a guessed token, from a peer that owns no slot.
            std::vector<uint8_t> d;
            switch (rng() % 4) {
                case 0:
                    d.resize(1 + rng() % 80);
                    for (auto& b : d) b = static_cast<uint8_t>(rng());
                    break;
                case 1: {
                    Inputs in{static_cast<uint8_t>(rng() % 2), static_cast<int32_t>(rng() % 400),
                              std::vector<uint8_t>(8 * (1 + rng() % 4))};
                    for (auto& b : in.bytes) b = static_cast<uint8_t>(rng());
                    d = Datagram(Header{kProtocolVersion, static_cast<uint32_t>(rng()), 0},
                                 {in, HashReport{static_cast<int32_t>(rng() % 300), rng()}}, shape);
                    d.resize(kHeaderBytes + rng() % (d.size() - kHeaderBytes + 1));
                    break;
                }
                case 2: {
                    d = Datagram(Header{kProtocolVersion, static_cast<uint32_t>(rng()), 0},
                                 {ConfirmedAck{static_cast<int32_t>(rng() % 1000)}, Ping{rng()},
                                  Disconnect{RejectReason::e_left}},
                                 shape);
                    d[kHeaderBytes + rng() % (d.size() - kHeaderBytes)] ^= static_cast<uint8_t>(1u << (rng() % 8));
                    break;
                }
                default:
                    d = Datagram(Header{static_cast<uint8_t>(rng() % 3), static_cast<uint32_t>(rng()), 0},
                                 {Hello{static_cast<uint32_t>(rng()), static_cast<uint32_t>(rng()),
                                        static_cast<uint8_t>(rng()), 0}},
                                 shape);
                    break;
            }
            attacker.Send(0, d);
            ++sent;
            for (size_t i = 0; i < m.players(); ++i)
                if (m.player(i).client->Frame() < s.frames) return false;
            return true;
        },
        60'000);
    ASSERT_TRUE(done);
    const ServerStats& st = m.server().Stats();
    EXPECT_GT(st.MalformedTotal() + st.unknownPeer + st.rejected + st.badToken, sent / 2);
    EXPECT_EQ(m.player(0).hashAtStop, m.player(1).hashAtStop);
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_desync), 0u);
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_disconnected), 0u);
}

TEST(LockstepSession, SilentClientIsInterruptedThenDisconnectedAndTheMatchGoesOn) {
    MatchSpec s = Spec(105, 3);
    s.frames = 400;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(100, 60'000));
    Player& gone = m.player(2);
    const int32_t slot = gone.client->Slot();
    gone.paused = true;
    gone.endpoint.SetDown(true);
    const uint64_t downAt = m.net().NowMicros();
    uint64_t interruptedAt = 0, disconnectedAt = 0;
    m.RunUntil(
        [&] {
            for (const ServerEvent& e : m.serverEvents()) {
                if (e.slot != slot) continue;
                if (e.kind == ServerEvent::Kind::e_interrupted && interruptedAt == 0)
                    interruptedAt = m.net().NowMicros();
                if (e.kind == ServerEvent::Kind::e_disconnected && disconnectedAt == 0)
                    disconnectedAt = m.net().NowMicros();
            }
            return disconnectedAt != 0;
        },
        5'000);
    ASSERT_NE(interruptedAt, 0u);
    ASSERT_NE(disconnectedAt, 0u);
    // Silence counts from the last datagram heard, which was still in flight when the client
    // went down: up to one one-way delay (20 ms + 5 ms jitter) later, plus the 1 ms update step.
    const uint64_t inFlight = 25'000 + 2'000;
    EXPECT_LE(interruptedAt - downAt, 500'000u + inFlight);
    EXPECT_LE(disconnectedAt - downAt, 2'000'000u + inFlight);
    EXPECT_GE(disconnectedAt - downAt, 1'500'000u);
    // The others go on with empty input for the dropped slot.
    ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
    EXPECT_EQ(m.player(0).hashAtStop, m.player(1).hashAtStop);
    EXPECT_EQ(m.server().Slot(static_cast<uint32_t>(slot)).state, SlotInfo::State::e_disconnected);
    const int32_t late = m.server().ConfirmedFrames() - 1;
    const std::span<const uint8_t> row = m.server().ConfirmedInputs(late);
    for (size_t b = 0; b < 8; ++b) EXPECT_EQ(row[static_cast<size_t>(slot) * 8 + b], 0);
}

TEST(LockstepSession, ClientSeesTheServerGoSilent) {
    MatchSpec s = Spec(106, 2);
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(60, 60'000));
    m.net().Endpoint(0).SetDown(true);
    Player& p = m.player(0);
    ASSERT_TRUE(m.RunUntil([&] { return p.client->State() == ClientState::e_closed; }, 3'000));
    bool interrupted = false, disconnected = false;
    for (const ClientEvent& e : p.events) {
        interrupted = interrupted || e.kind == ClientEvent::Kind::e_interrupted;
        disconnected =
            disconnected || (e.kind == ClientEvent::Kind::e_disconnected && e.reason == RejectReason::e_timeout);
    }
    EXPECT_TRUE(interrupted);
    EXPECT_TRUE(disconnected);
}

void LateJoin(bool authoritative, uint64_t seed) {
    MatchSpec s = Spec(seed, 2);
    s.extraSlots = 1;
    s.frames = 500;
    s.hashInterval = 20;
    s.authoritative = authoritative;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(150, 60'000));
    Player& joiner = m.AddPlayer();
    ASSERT_TRUE(m.RunUntil([&] { return joiner.client->State() == ClientState::e_running; }, 10'000))
        << "state " << static_cast<int>(joiner.client->State());
    ASSERT_TRUE(m.RunToFrame(s.frames, 60'000));
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_admitted), 1u);
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_joinFailed), 0u);
    EXPECT_EQ(m.CountServerEvents(ServerEvent::Kind::e_desync), 0u);
    for (size_t i = 0; i < m.players(); ++i) EXPECT_EQ(m.player(i).hashAtStop, m.player(0).hashAtStop) << i;
    // The joiner's inputs count after its join frame.
    int32_t joinFrame = -1;
    for (const ClientEvent& e : joiner.events)
        if (e.kind == ClientEvent::Kind::e_admitted) joinFrame = e.frame;
    ASSERT_GE(joinFrame, 150);
    bool any = false;
    for (int32_t f = joinFrame; f < m.server().ConfirmedFrames() && !any; ++f) {
        const auto row = m.server().ConfirmedInputs(f);
        for (size_t b = 0; b < 8; ++b) any = any || row[static_cast<size_t>(joiner.client->Slot()) * 8 + b] != 0;
    }
    EXPECT_TRUE(any) << "the joiner's inputs never reached the match";
}

TEST(LockstepSession, LateJoinThroughARelayedClientSnapshot) { LateJoin(false, 107); }
TEST(LockstepSession, LateJoinFromTheAuthoritativeServer) { LateJoin(true, 108); }

TEST(LockstepSession, ReconnectTakesTheSlotBack) {
    MatchSpec s = Spec(109, 2);
    s.frames = 500;
    s.hashInterval = 20;
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(100, 60'000));
    Player& old = m.player(1);
    const int32_t slot = old.client->Slot();
    const uint32_t token = old.client->Token();
    old.paused = true;
    old.endpoint.SetDown(true);
    ASSERT_TRUE(m.RunUntil([&] { return m.CountServerEvents(ServerEvent::Kind::e_disconnected) == 1; }, 3'000));
    ClientConfig again;
    again.reconnectToken = token;
    Player& back = m.AddPlayer(again);
    ASSERT_TRUE(m.RunUntil([&] { return back.client->State() == ClientState::e_running; }, 10'000));
    EXPECT_EQ(back.client->Slot(), slot);
    EXPECT_EQ(back.client->Token(), token);
    old.stopFrame = -1;  // the frozen one never gets there
    ASSERT_TRUE(m.RunUntil([&] { return m.player(0).client->Frame() >= s.frames && back.client->Frame() >= s.frames; },
                           60'000));
    EXPECT_EQ(back.hashAtStop, m.player(0).hashAtStop);
}

TEST(LockstepSession, FullServerRejects) {
    MatchSpec s = Spec(110, 2);
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(30, 60'000));
    Player& extra = m.AddPlayer();
    extra.stopFrame = -1;
    ASSERT_TRUE(m.RunUntil([&] { return extra.client->State() == ClientState::e_closed; }, 2'000));
    ASSERT_FALSE(extra.events.empty());
    EXPECT_EQ(extra.events.back().kind, ClientEvent::Kind::e_rejected);
    EXPECT_EQ(extra.events.back().reason, RejectReason::e_full);
}

TEST(LockstepSession, OtherProtocolVersionIsTold) {
    MatchSpec s = Spec(111, 1);
    SCOPED_TRACE(s.Describe());
    Match m(s);
    SimEndpoint& old = m.net().AddEndpoint();
    Header h;
    h.version = kProtocolVersion + 1;
    old.Send(0, Datagram(h, {KeepAlive{}}, SessionShape{}));
    std::vector<lockbox::net::Datagram> got;
    m.RunUntil(
        [&] {
            old.Poll(got);
            return !got.empty();
        },
        1'000);
    ASSERT_EQ(got.size(), 1u);
    Header back;
    std::vector<Message> msgs;
    ASSERT_EQ(DecodeDatagram(got[0].bytes, SessionShape{}, back, msgs), DecodeError::e_ok);
    ASSERT_EQ(msgs.size(), 1u);
    ASSERT_TRUE(std::holds_alternative<Reject>(msgs[0]));
    EXPECT_EQ(std::get<Reject>(msgs[0]).reason, RejectReason::e_protocolVersion);
    EXPECT_EQ(m.server().Stats().malformed[static_cast<size_t>(DecodeError::e_badVersion)], 1u);
}

TEST(LockstepSession, GracefulLeaveIsImmediate) {
    MatchSpec s = Spec(112, 2);
    SCOPED_TRACE(s.Describe());
    Match m(s);
    ASSERT_TRUE(m.RunToFrame(60, 60'000));
    m.player(1).client->Leave();
    m.player(1).paused = true;
    ASSERT_TRUE(m.RunUntil([&] { return m.CountServerEvents(ServerEvent::Kind::e_disconnected) == 1; }, 200));
    for (const ServerEvent& e : m.serverEvents()) {
        if (e.kind == ServerEvent::Kind::e_disconnected) {
            EXPECT_EQ(e.reason, RejectReason::e_left);
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::testing
