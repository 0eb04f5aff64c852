// Disconnect agreement with 3+ peers (docs/rollback.md "Disconnects"): survivors
// that received different amounts of a leaver's inputs still cut it at the same frame, and
// every final hash agrees before and after the cut. Session-level cases first (no network),
// then SimNet matches through rollback_harness.h.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "RollbackMixGame.h"
#include "rollback_leave.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

// ---- Session level: three sessions of a 3-player game wired by hand --------------------

std::vector<uint8_t> Byte(uint8_t v) { return std::vector<uint8_t>(2, v); }

std::unique_ptr<RollbackSession> Three(uint32_t local) {
    return RollbackSessionBuilder()
        .Players(3)
        .InputBytes(2)
        .LocalPlayer(local)
        .PredictionWindow(8)
        .DesyncInterval(1)
        .Build();
}

// Player f's input at frame f: varies, so predictions miss and cuts matter.
uint8_t Scripted(uint32_t player, int32_t frame) { return static_cast<uint8_t>((frame * 7 + player * 13) % 5); }

// One tick of session `s` with local player `me`: its scripted input, then AdvanceFrame.
void Tick(RollbackSession& s, MixGame& t, uint32_t me) {
    s.AddLocalInput(me, Byte(Scripted(me, s.CurrentFrame())));
    t.Run(s, s.AdvanceFrame());
}

// What session `from` holds, as its RollbackPeer would send it.
std::vector<int32_t> ViewOf(const RollbackSession& from) {
    std::vector<int32_t> v;
    for (uint32_t p = 0; p < 3; ++p) v.push_back(from.ReceivedFrame(p));
    return v;
}

// Sessions 0 and 1 survive; player 2 leaves after session 0 got 20 of its inputs and session
// 1 got 30. Each freezes at its own count; with the other's value both cut at 20 and every
// frame gets the same inputs on both.
TEST(RollbackDisconnectSession, DifferentFreezesGiveOneCutAndTheSameInputs) {
    auto a = Three(0), b = Three(1);
    MixGame ta, tb;
    for (int32_t f = 0; f < 100; ++f) {
        ASSERT_EQ(a->AddRemoteInput(1, f, Byte(Scripted(1, f))), InputResult::e_ok);
        ASSERT_EQ(b->AddRemoteInput(0, f, Byte(Scripted(0, f))), InputResult::e_ok);
        if (f < 20) a->AddRemoteInput(2, f, Byte(Scripted(2, f)));
        if (f < 30) b->AddRemoteInput(2, f, Byte(Scripted(2, f)));
    }
    // The window stops a at 28 and b at 38 (8 frames past player 2's last input); each
    // knows what the other holds, as RollbackPeer's views tell it.
    for (int t = 0; t < 40; ++t) {
        a->SetPeerView(1, ViewOf(*b));
        b->SetPeerView(0, ViewOf(*a));
        Tick(*a, ta, 0);
        Tick(*b, tb, 1);
    }
    ASSERT_EQ(a->CurrentFrame(), 28);
    ASSERT_EQ(b->CurrentFrame(), 38);
    // b holds player 2 up to 30, but a only up to 20: nothing past 20 is final on b.
    EXPECT_LE(b->ConfirmedFrame(), 20);
    EXPECT_EQ(a->FreezePlayer(2), 20);
    EXPECT_EQ(b->FreezePlayer(2), 30);
    EXPECT_EQ(b->FreezePlayer(2), 30);  // the same value again
    EXPECT_EQ(b->AddRemoteInput(2, 30, Byte(1)), InputResult::e_disconnected);
    EXPECT_TRUE(a->ReportFrozen(2, 30));
    EXPECT_TRUE(b->ReportFrozen(2, 20));
    EXPECT_EQ(a->CompleteDisconnect(2), 20);
    EXPECT_EQ(b->CompleteDisconnect(2), 20);
    EXPECT_EQ(a->CompleteDisconnect(2), -1);  // once
    EXPECT_EQ(b->ReceivedFrame(2), 20);       // inputs past the cut are forgotten
    EXPECT_TRUE(b->ConfirmedInput(2, 25).empty());
    for (RollbackSession* s : {a.get(), b.get()}) {
        int disconnects = 0;
        for (const RollbackEvent& e : s->TakeEvents())
            if (e.kind == RollbackEvent::Kind::e_disconnected) {
                ++disconnects;
                EXPECT_EQ(e.player, 2u);
                EXPECT_EQ(e.frame, 20);
            }
        EXPECT_EQ(disconnects, 1);
    }
    for (int t = 0; t < 60; ++t) {
        a->SetPeerView(1, ViewOf(*b));
        b->SetPeerView(0, ViewOf(*a));
        if (a->CurrentFrame() < 60) Tick(*a, ta, 0);
        if (b->CurrentFrame() < 60) Tick(*b, tb, 1);
    }
    ASSERT_EQ(a->CurrentFrame(), 60);
    ASSERT_EQ(b->CurrentFrame(), 60);
    ASSERT_EQ(ta.inputs.size(), 60u);
    ASSERT_EQ(tb.inputs.size(), 60u);
    for (int32_t f = 0; f < 60; ++f) {
        SCOPED_TRACE(::testing::Message() << "frame " << f);
        EXPECT_EQ(ta.inputs[f], tb.inputs[f]);
        EXPECT_EQ(ta.inputs[f][4], f < 20 ? Scripted(2, f) : 0);
    }
    EXPECT_EQ(ta.state, tb.state);
    // Both had simulated frames from 20 on with other inputs for player 2 (b the real ones,
    // a a prediction): both rolled back.
    EXPECT_GE(a->Stats().rollbacks, 1u);
    EXPECT_GE(b->Stats().rollbacks, 1u);
    EXPECT_EQ(a->ConfirmedFrame(), 60);
    ASSERT_FALSE(a->FinalHashes().empty());
}

// A frame at or past what a live remote peer holds never becomes final, whatever this
// session holds; it does once the view moves on.
TEST(RollbackDisconnectSession, NothingPastARemoteViewBecomesFinal) {
    auto s = Three(0);
    MixGame t;
    const std::vector<int32_t> nothing{0, 0, 0};
    s->SetPeerView(1, nothing);
    s->SetPeerView(2, nothing);
    for (int32_t f = 0; f < 6; ++f) {
        s->AddLocalInput(0, Byte(1));
        s->AddRemoteInput(1, f, Byte(2));
        s->AddRemoteInput(2, f, Byte(3));
        t.Run(*s, s->AdvanceFrame());
    }
    EXPECT_EQ(s->HeldFrame(), 6);
    EXPECT_EQ(s->ConfirmedFrame(), 0);
    EXPECT_TRUE(s->FinalHashes().size() <= 1);  // frame 0 only
    s->SetPeerView(1, std::vector<int32_t>{6, 6, 6});
    s->SetPeerView(2, std::vector<int32_t>{4, 6, 6});
    EXPECT_EQ(s->ConfirmedFrame(), 4);
    s->SetPeerView(2, std::vector<int32_t>{3, 6, 6});  // reordered, older: ignored
    EXPECT_EQ(s->ConfirmedFrame(), 4);
    t.Run(*s, s->AdvanceFrame());
    ASSERT_FALSE(s->FinalHashes().empty());
    EXPECT_EQ(s->FinalHashes().back().first, 4);
    // Peer 2 leaves: its view stops counting, player 2 is frozen at 6 and cut there.
    s->DropPeer(2);
    EXPECT_EQ(s->FreezePlayer(2), 6);
    EXPECT_EQ(s->ConfirmedFrame(), 6);
    EXPECT_FALSE(s->ReportFrozen(2, 3));  // below the final frame: refused
    EXPECT_EQ(s->Stats().frozenReportsIgnored, 1u);
    EXPECT_EQ(s->CompleteDisconnect(2), 6);
    EXPECT_TRUE(s->IsDisconnected(2));
    EXPECT_EQ(s->CutFrame(2), 6);
}

// ---- SimNet matches --------------------------------------------------------------------

class RollbackLeave : public ::testing::TestWithParam<Leave> {};

TEST_P(RollbackLeave, SurvivorsAgreeOnTheCut) {
    const Leave c = GetParam();
    RunLeaveCell(c, 31000 + c.peers * 1000 + c.rtt * 10 + c.loss + (c.graceful ? 500 : 0));
}

// A subset here (each peer count, leave mode, RTT and loss at least once); the full
// {3, 4} peers x {down, RbDisconnect} x RTT {0, 50} x loss {0, 5} matrix is in
// heavy/rollback_disconnect_matrix_test.cpp.
std::vector<Leave> LeaveCells() {
    return {Leave{3, 50, 5, 30, false}, Leave{3, 0, 0, 30, true}, Leave{4, 0, 5, 30, false}, Leave{4, 50, 5, 30, true}};
}

INSTANTIATE_TEST_SUITE_P(Subset, RollbackLeave, ::testing::ValuesIn(LeaveCells()));

// Through a relay: the leaver's datagrams to peer 0 vanish before it goes down.
TEST(RollbackLeaveMore, RelayedThreePeers) {
    for (bool graceful : {false, true}) {
        RbSpec spec = LeaveSpec(Leave{3, 50, 5, 30, graceful}, 33100 + (graceful ? 1 : 0));
        spec.relayed = true;
        spec.spectator = true;
        const RbResult r = RunRbMatch(spec);
        ExpectAgreement(spec, r, 300);
        // The spectator, fed by survivor 0, steps the zeros of the cut too.
        EXPECT_GE(CompareSpectator(spec, r), 40u) << spec.Describe();
    }
}

// Two leavers one after the other (4 peers: 3 leaves first, then 2), and a second leaver that
// dies while the first agreement is pending (its frozen value never comes).
TEST(RollbackLeaveMore, TwoPeersLeaveOneAfterTheOther) {
    {
        RbSpec spec;
        spec.seed = 34001;
        spec.peers = 4;
        spec.rttMs = 50;
        spec.lossPct = 5;
        spec.jitterMs = 30;
        spec.frames = 1000;
        spec.linkCuts = {RbLinkCut{3, 0, 150}, RbLinkCut{2, 1, 420}};
        spec.exits = {RbExit{3, 180, false}, RbExit{2, 450, true}};
        const RbResult r = RunRbMatch(spec);
        const auto cuts = ExpectAgreement(spec, r, 300);
        EXPECT_EQ(cuts.size(), 2u) << spec.Describe();
    }
    {
        RbSpec spec;
        spec.seed = 34002;
        spec.peers = 4;
        spec.rttMs = 50;
        spec.jitterMs = 30;
        spec.frames = 800;
        spec.linkCuts = {RbLinkCut{3, 0, 150}};
        // Peer 2 goes down before anyone times peer 3 out (2 s after 150): survivors wait
        // for its frozen value of player 3 until they time peer 2 out too.
        spec.exits = {RbExit{3, 180, false}, RbExit{2, 200, false}};
        const RbResult r = RunRbMatch(spec);
        const auto cuts = ExpectAgreement(spec, r, 300);
        EXPECT_EQ(cuts.size(), 2u) << spec.Describe();
    }
}

// Eight peers (the most a session takes), three leaving: peer 7 abruptly after its link to
// peer 0 died, peer 6 with RbDisconnect, and peer 5 going down while the agreement about
// peer 7 is still pending. The five survivors agree on each cut.
TEST(RollbackLeaveMore, ThreeOfEightPeersLeave) {
    RbSpec spec;
    spec.seed = 36001;
    spec.peers = kRollbackMaxPlayers;
    spec.rttMs = 50;
    spec.lossPct = 5;
    spec.jitterMs = 30;
    spec.frames = 900;
    spec.linkCuts = {RbLinkCut{7, 0, 150}};
    spec.exits = {RbExit{7, 180, false}, RbExit{6, 300, true}, RbExit{5, 200, false}};
    const RbResult r = RunRbMatch(spec);
    const auto cuts = ExpectAgreement(spec, r, 300);
    EXPECT_EQ(cuts.size(), 3u) << spec.Describe();
}

// A half-broken link: peer 2's datagrams stop reaching peer 0, while peer 1 still hears it
// and peer 2 never leaves. Peer 0 times it out and says so; peer 1 cuts it too (gossip) at
// peer 0's smaller frozen frame, although it still hears it. Peer 2, named gone, is out of
// the match: it is told so at once (e_removed), stops hearing the others and plays on alone.
TEST(RollbackLeaveMore, HalfBrokenLinkGossip) {
    RbSpec spec;
    spec.seed = 35001;
    spec.peers = 3;
    spec.rttMs = 50;
    spec.lossPct = 5;
    spec.jitterMs = 30;
    spec.frames = 800;
    spec.linkCuts = {RbLinkCut{2, 0, 150}};
    const RbResult r = RunRbMatch(spec);
    ExpectAgreement(spec, r, 300, false, {2});
    EXPECT_FALSE(r.peers[1].net->RemoteAlive(1)) << spec.Describe();  // peer 1's remotes: 0, 2
    EXPECT_LT(r.peers[0].session->FrozenFrame(2), r.peers[1].session->FrozenFrame(2)) << spec.Describe();
    EXPECT_FALSE(r.peers[2].session->IsDisconnected(2)) << spec.Describe();  // its own player: never
    // Peer 2 learns it was named gone once, at a frame one of the others froze it at.
    int removed = 0;
    for (const RollbackEvent& e : r.peers[2].events) {
        if (e.kind != RollbackEvent::Kind::e_removed) continue;
        ++removed;
        EXPECT_EQ(e.player, 2u);
        EXPECT_TRUE(e.frame == r.peers[0].session->FrozenFrame(2) || e.frame == r.peers[1].session->FrozenFrame(2))
            << "removed at " << e.frame << "; " << spec.Describe();
    }
    EXPECT_EQ(removed, 1) << spec.Describe();
    EXPECT_TRUE(r.peers[2].net->RemovedFromMatch());
    // The survivors were never named gone.
    for (uint32_t i = 0; i < 2; ++i) {
        EXPECT_FALSE(r.peers[i].net->RemovedFromMatch());
        for (const RollbackEvent& e : r.peers[i].events) EXPECT_NE(e.kind, RollbackEvent::Kind::e_removed);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
