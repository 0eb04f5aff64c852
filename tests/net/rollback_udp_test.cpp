// Two rollback peers over real UDP sockets on 127.0.0.1 (bounded: 4,000 loop turns and 20 wall
// seconds): the same session code as on SimNet reaches the same confirmed states.

#include <chrono>
#include <map>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/replay/SceneGame.h"
#include "rollback_udp_start.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

TEST(RollbackUdp, TwoPeersOnLoopbackAgree) {
    SCOPED_TRACE("seed=31");
    std::string error;
    auto ta = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_NE(ta, nullptr) << error;
    auto tb = UdpTransport::Open("127.0.0.1", 0, &error);
    ASSERT_NE(tb, nullptr) << error;
    const PeerId aToB = ta->AddPeer("127.0.0.1", tb->LocalPort(), &error);
    const PeerId bToA = tb->AddPeer("127.0.0.1", ta->LocalPort(), &error);
    ASSERT_NE(aToB, kNoPeer);
    ASSERT_NE(bToA, kNoPeer);
    Transport* transports[2] = {ta.get(), tb.get()};
    const PeerId others[2] = {aToB, bToA};

    struct Side {
        std::unique_ptr<replay::SceneGame> game;
        std::unique_ptr<RollbackSession> session;
        std::unique_ptr<WorldGameAdapter> adapter;
        std::unique_ptr<RollbackPeer> peer;
        std::unique_ptr<replay::ScriptedInputs> script;
        std::map<int32_t, uint64_t> finals;
        bool desync = false, failed = false;
    } sides[2];
    for (uint32_t i = 0; i < 2; ++i) {
        Side& s = sides[i];
        rbtest::BuildUdpSide(s, i, *transports[i], {others[i]}, 31);
    }
    const int32_t frames = 150;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    std::vector<uint8_t> input;
    bool done = false;
    for (int turn = 0; turn < 4000 && !done && std::chrono::steady_clock::now() < deadline; ++turn) {
        done = true;
        for (uint32_t i = 0; i < 2; ++i) {
            Side& s = sides[i];
            s.peer->Poll();
            if (s.session->ReceivedFrame(i) <= s.session->CurrentFrame() + 1) {
                s.script->Next(input);
                s.session->AddLocalInput(i, input);
            }
            if (!s.adapter->Execute(*s.session, s.session->AdvanceFrame())) s.failed = true;
            s.peer->Flush();
            for (const auto& [f, h] : s.session->FinalHashes()) s.finals[f] = h;
            for (const auto& e : s.session->TakeEvents())
                if (e.kind == RollbackEvent::Kind::e_desync) s.desync = true;
            if (s.session->ConfirmedFrame() < frames) done = false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_TRUE(done);
    size_t common = 0;
    for (const auto& [f, h] : sides[0].finals) {
        auto it = sides[1].finals.find(f);
        if (it == sides[1].finals.end()) continue;
        ++common;
        EXPECT_EQ(it->second, h) << "frame " << f;
    }
    EXPECT_GE(common, 20u);
    for (const Side& s : sides) {
        EXPECT_FALSE(s.desync);
        EXPECT_FALSE(s.failed);
    }
}

// The start phase on real sockets: the second peer's port opens 500 ms after the first one
// starts sending to it, in either order (the 3 s case is heavy: rollback_start_udp_test.cpp).
TEST(RollbackUdp, PeersStartedApartOnLoopbackAgree) {
    for (uint32_t late = 0; late < 2; ++late) {
        SCOPED_TRACE(::testing::Message() << "late side " << late);
        rbtest::UdpStartResult r;
        const auto none = std::chrono::milliseconds(0), later = std::chrono::milliseconds(500);
        rbtest::RunUdpStaggered(r, {late == 0 ? later : none, late == 1 ? later : none}, 120);
        rbtest::ExpectUdpStartedTogether(r, 120);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
