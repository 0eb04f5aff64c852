// The state hash fold (StateHash.h, docs/rollback.md "The state hash"): a game that executes
// rollback requests with its own code and reports FoldUserState reports what
// WorldGameAdapter reports, rollbacks included, so the two can play one match.

#include <cstdint>
#include <cstring>
#include <map>
#include <span>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/StateHash.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

// A scene game with state beyond the world: a running sum of every input byte applied, four
// bytes little-endian, so the fold has user state to take in.
class ScoredGame : public WorldGame {
public:
    explicit ScoredGame(replay::SceneGame& inner) : m_inner(inner) {}
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        for (uint8 b : inputs) m_score += b;
        m_inner.Apply(world, frame, inputs);
    }
    void SaveUserState(std::vector<uint8>& out) const override {
        out.clear();
        for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8>(m_score >> (8 * i)));
    }
    void LoadUserState(std::span<const uint8> in) override {
        m_score = 0;
        for (size_t i = 0; i < 4 && i < in.size(); ++i) m_score |= uint32_t{in[i]} << (8 * i);
    }

private:
    replay::SceneGame& m_inner;
    uint32_t m_score = 0;
};

// What a game with its own executor writes: portable images instead of rollback frames, its own
// step, and the fold for the hash.
class OwnExecutor {
public:
    OwnExecutor(b2World& world, WorldGame& game) : m_world(world), m_game(game) {}
    bool Execute(RollbackSession& session, std::span<const RollbackRequest> requests) {
        for (const RollbackRequest& r : requests) {
            if (const auto* save = std::get_if<SaveState>(&r)) {
                Saved& s = m_saved[save->frame];
                m_world.Save(s.image);
                m_game.SaveUserState(s.user);
                if (save->wantHash) session.ReportHash(save->frame, FoldUserState(m_world.Hash(), s.user));
            } else if (const auto* load = std::get_if<LoadState>(&r)) {
                auto it = m_saved.find(load->frame);
                if (it == m_saved.end() || !m_world.Restore(it->second.image).ok()) return false;
                m_game.LoadUserState(it->second.user);
            } else if (const auto* adv = std::get_if<AdvanceRequest>(&r)) {
                m_game.Apply(m_world, adv->frame, adv->inputs);
                m_world.Step(Fixed::FromRatio(1, 60), 8, 3);
            }
        }
        return true;
    }

private:
    struct Saved {
        std::vector<uint8> image, user;
    };
    b2World& m_world;
    WorldGame& m_game;
    std::map<int32_t, Saved> m_saved;
};

TEST(StateHash, FoldKeepsTheWorldHashWithoutUserState) {
    EXPECT_EQ(FoldUserState(0x0123456789ABCDEFull, std::span<const uint8_t>{}), 0x0123456789ABCDEFull);
    const std::vector<uint8_t> a{1, 2, 3}, b{1, 2, 4};
    EXPECT_NE(FoldUserState(7, a), 7u);
    EXPECT_NE(FoldUserState(7, a), FoldUserState(7, b));
    EXPECT_NE(FoldUserState(7, a), FoldUserState(8, a));
}

// The same inputs, arriving late so that both sessions roll back, through the adapter on one
// world and through the game's own executor on another: every hash the sessions compare is the
// same, and the adapter's StateHash is FoldedStateHash.
TEST(StateHash, OwnExecutorAgreesWithTheAdapter) {
    replay::SceneGame sceneA("vertical_stack"), sceneB("vertical_stack");
    ScoredGame gameA(sceneA), gameB(sceneB);
    auto build = [] {
        return RollbackSessionBuilder()
            .Players(2)
            .InputBytes(replay::SceneInput::kBytes)
            .LocalPlayer(0)
            .PredictionWindow(8)
            .DesyncInterval(1)
            .Build();
    };
    auto sessionA = build(), sessionB = build();
    WorldGameAdapter adapter(sceneA.world(), gameA, WorldStepSettings{60, 8, 3});
    OwnExecutor own(sceneB.world(), gameB);
    replay::ScriptedInputs local(91, 1), remote(92, 1);
    std::vector<uint8_t> in;
    std::vector<std::vector<uint8_t>> remoteInputs;
    std::map<int32_t, uint64_t> finalsA, finalsB;
    for (int32_t tick = 0; tick < 300; ++tick) {
        local.Next(in);
        ASSERT_EQ(sessionA->AddLocalInput(0, in), InputResult::e_ok);
        ASSERT_EQ(sessionB->AddLocalInput(0, in), InputResult::e_ok);
        // The remote player's input of frame f arrives at tick f + 3: predictions, some wrong.
        remote.Next(in);
        remoteInputs.push_back(in);
        if (tick >= 3) {
            const int32_t f = tick - 3;
            ASSERT_EQ(sessionA->AddRemoteInput(1, f, remoteInputs[static_cast<size_t>(f)]), InputResult::e_ok);
            ASSERT_EQ(sessionB->AddRemoteInput(1, f, remoteInputs[static_cast<size_t>(f)]), InputResult::e_ok);
        }
        ASSERT_TRUE(adapter.Execute(*sessionA, sessionA->AdvanceFrame()));
        ASSERT_TRUE(own.Execute(*sessionB, sessionB->AdvanceFrame()));
        for (const auto& [f, h] : sessionA->FinalHashes()) finalsA[f] = h;
        for (const auto& [f, h] : sessionB->FinalHashes()) finalsB[f] = h;
    }
    EXPECT_GT(sessionA->Stats().rollbacks, 10u);
    EXPECT_EQ(sessionA->Stats().rollbacks, sessionB->Stats().rollbacks);
    ASSERT_GE(finalsA.size(), 250u);
    EXPECT_EQ(finalsA, finalsB);
    EXPECT_EQ(adapter.StateHash(), FoldedStateHash(sceneB.world(), gameB));
    // The user state takes part: the folded hash is not the world's alone.
    EXPECT_NE(adapter.StateHash(), sceneA.world().Hash());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
