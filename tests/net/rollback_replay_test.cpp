// Replays recorded by rollback matches (WorldGameAdapter::Record): every peer simulates once,
// records its final frames, and the files of all peers that played to the end are the same
// bytes, verify, and equal the file a single world recording the confirmed inputs writes.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/SimNet.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

constexpr uint64_t kTick = 16666;

// A scene game with state beyond the world: a running sum over the inputs it was given. A
// keyframe saved with a predicted frame's user state would differ from a single world's.
class TallyGame : public WorldGame {
public:
    explicit TallyGame(replay::SceneGame& inner) : m_inner(inner) {}
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        for (size_t i = 0; i < inputs.size(); ++i) m_tally = m_tally * 31 + inputs[i] + static_cast<uint64_t>(frame);
        m_inner.Apply(world, frame, inputs);
    }
    void SaveUserState(std::vector<uint8>& out) const override {
        out.resize(8);
        for (int i = 0; i < 8; ++i) out[static_cast<size_t>(i)] = static_cast<uint8>(m_tally >> (8 * i));
    }
    void LoadUserState(std::span<const uint8> in) override {
        m_tally = 0;
        for (size_t i = 0; i < in.size() && i < 8; ++i) m_tally |= uint64_t{in[i]} << (8 * i);
    }

private:
    replay::SceneGame& m_inner;
    uint64_t m_tally = 0;
};

struct Spec {
    uint32_t peers = 2;
    uint32_t rttMs = 80, jitterMs = 20, lossPct = 5;
    int32_t frames = 300;   ///< frames every recording holds
    int32_t downPeer = -1;  ///< this peer's machine goes down at downTick
    int64_t downTick = 0;
    const char* scene = "vertical_stack";
    uint64_t seed = 3;
};

struct Side {
    std::unique_ptr<replay::SceneGame> scene;
    std::unique_ptr<TallyGame> game;
    std::unique_ptr<RollbackSession> session;
    std::unique_ptr<WorldGameAdapter> adapter;
    std::unique_ptr<RollbackPeer> peer;
    std::unique_ptr<replay::ScriptedInputs> inputs;
    std::unique_ptr<replay::MemorySink> sink;
    std::unique_ptr<replay::Recorder> recorder;
    std::vector<uint8_t> pending;
    bool hasPending = false;
    bool executeFailed = false;
};

replay::RecorderConfig ConfigFor(const replay::SceneGame& scene, uint32_t players) {
    replay::RecorderConfig c = scene.Config(static_cast<uint16>(players));
    c.keyframeInterval = 90;  // several keyframes, taken at frames rolled back over
    return c;
}

std::vector<Side> Play(const Spec& spec) {
    SimNet net(spec.seed);
    LinkProfile link;
    link.latencyMicros = spec.rttMs * 500u;
    link.jitterMicros = spec.jitterMs * 1000u;
    link.lossPpm = spec.lossPct * 10000u;
    std::vector<SimEndpoint*> ends;
    for (uint32_t i = 0; i < spec.peers; ++i) ends.push_back(&net.AddEndpoint());
    net.SetAllLinks(link);
    std::vector<Side> sides(spec.peers);
    for (uint32_t i = 0; i < spec.peers; ++i) {
        Side& s = sides[i];
        s.scene = std::make_unique<replay::SceneGame>(spec.scene);
        s.game = std::make_unique<TallyGame>(*s.scene);
        s.session = RollbackSessionBuilder()
                        .Players(spec.peers)
                        .InputBytes(replay::SceneInput::kBytes)
                        .LocalPlayer(i)
                        .InputDelay(1)
                        .Build();
        const auto& info = s.scene->info();
        s.adapter = std::make_unique<WorldGameAdapter>(
            s.scene->world(), *s.game,
            WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                              static_cast<uint32_t>(info.positionIterations)});
        s.sink = std::make_unique<replay::MemorySink>();
        s.recorder =
            std::make_unique<replay::Recorder>(s.scene->world(), *s.game, *s.sink, ConfigFor(*s.scene, spec.peers));
        EXPECT_TRUE(s.adapter->Record(*s.recorder, spec.frames));
        RollbackPeerConfig cfg;
        cfg.matchId = 28;
        for (uint32_t j = 0; j < spec.peers; ++j)
            if (j != i) cfg.remotes.push_back(RollbackRemote{ends[j]->Index(), {j}});
        s.peer = std::make_unique<RollbackPeer>(*s.session, *ends[i], cfg);
        s.inputs = std::make_unique<replay::ScriptedInputs>(spec.seed * 100 + i, 1);
    }
    const int64_t limit = int64_t{spec.frames} * 4 + 600;
    for (int64_t tick = 0; tick < limit; ++tick) {
        bool done = true;
        for (uint32_t i = 0; i < spec.peers; ++i) {
            Side& s = sides[i];
            if (static_cast<int32_t>(i) == spec.downPeer && tick >= spec.downTick) {
                ends[i]->SetDown(true);
                continue;
            }
            s.peer->Poll();
            if (!s.peer->WaitThisTick()) {
                if (!s.hasPending) {
                    s.inputs->Next(s.pending);
                    s.hasPending = true;
                }
                if (s.session->AddLocalInput(i, s.pending) != InputResult::e_alreadyAdded) s.hasPending = false;
                const auto requests = s.session->AdvanceFrame();
                if (!s.adapter->Execute(*s.session, requests)) s.executeFailed = true;
            }
            s.peer->Flush();
            if (!s.adapter->RecordingFinished()) done = false;
        }
        net.Advance(kTick);
        if (done) break;
    }
    return sides;
}

// The file a single world writes from the same inputs with Recorder::Advance.
std::vector<uint8_t> RecordFresh(const Spec& spec, const replay::ReplayFile& file) {
    replay::SceneGame scene(spec.scene);
    TallyGame game(scene);
    replay::MemorySink sink;
    replay::Recorder recorder(scene.world(), game, sink, ConfigFor(scene, spec.peers));
    EXPECT_TRUE(recorder.Begin().ok());
    for (int32_t f = 0; f < file.frameCount; ++f) recorder.Advance(file.Inputs(f));
    EXPECT_TRUE(recorder.Finish().ok());
    return sink.bytes();
}

void ExpectVerifies(const Spec& spec, const replay::ReplayFile& file) {
    replay::SceneGame scene(spec.scene);
    TallyGame game(scene);
    replay::Player player(file, scene.world(), game);
    const replay::VerifyResult r = player.Verify();
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.hashesChecked, spec.frames);
    // Seeking to a keyframe restores the confirmed user state with it.
    ASSERT_FALSE(file.keyframes.empty());
    EXPECT_TRUE(player.Seek(file.keyframes.back().frame).ok());
}

// Checks every surviving peer's replay; returns peer `first`'s parsed file.
replay::ReplayFile CheckReplays(const Spec& spec, const std::vector<Side>& sides, uint32_t first) {
    const std::vector<uint8_t>& bytes = sides[first].sink->bytes();
    replay::ReplayFile file;
    for (uint32_t i = 0; i < sides.size(); ++i) {
        if (static_cast<int32_t>(i) == spec.downPeer) continue;
        const Side& s = sides[i];
        EXPECT_FALSE(s.executeFailed) << "peer " << i;
        EXPECT_TRUE(s.adapter->RecordingFinished()) << "peer " << i;
        EXPECT_FALSE(s.adapter->RecordingFailed()) << "peer " << i;
        EXPECT_EQ(s.adapter->RecordedFrames(), spec.frames) << "peer " << i;
        EXPECT_GT(s.session->Stats().rollbacks, 0u) << "peer " << i << ": the match should roll back";
        EXPECT_TRUE(s.sink->bytes() == bytes) << "peer " << i << "'s replay differs from peer " << first << "'s";
    }
    ::testing::Test::RecordProperty("replay_bytes", static_cast<int>(bytes.size()));
    const replay::Error e = replay::ParseReplay(bytes, file);
    EXPECT_TRUE(e.ok()) << e.Describe();
    EXPECT_EQ(file.frameCount, spec.frames);
    EXPECT_EQ(file.keyframes.size(), static_cast<size_t>(spec.frames / 90));
    ExpectVerifies(spec, file);
    EXPECT_TRUE(RecordFresh(spec, file) == bytes) << "a single world recording the same inputs writes other bytes";
    return file;
}

TEST(RollbackReplay, BothPeersRecordTheSameVerifiedReplay) {
    Spec spec;
    const std::vector<Side> sides = Play(spec);
    const replay::ReplayFile file = CheckReplays(spec, sides, 0);
    // The inputs are every player's confirmed ones.
    for (int32_t f = 0; f < file.frameCount; ++f)
        for (uint32_t p = 0; p < spec.peers; ++p) {
            const auto in = file.Inputs(f).subspan(p * replay::SceneInput::kBytes, replay::SceneInput::kBytes);
            const auto held = sides[p].session->ConfirmedInput(p, f);
            if (held.empty()) continue;  // older than the session keeps
            ASSERT_TRUE(std::equal(in.begin(), in.end(), held.begin(), held.end())) << "frame " << f;
        }
}

TEST(RollbackReplay, SpawningSceneRecordsTheSameReplay) {
    Spec spec;
    spec.scene = "rain";
    spec.frames = 100;  // one keyframe; rain's rows of bodies make later frames dear under ASan
    spec.seed = 5;
    CheckReplays(spec, Play(spec), 0);
}

TEST(RollbackReplay, DisconnectCutIsRecordedAsZeroInputs) {
    Spec spec;
    spec.peers = 3;
    spec.frames = 420;
    spec.downPeer = 2;
    spec.downTick = 120;
    const std::vector<Side> sides = Play(spec);
    const int32_t cut = sides[0].session->CutFrame(2);
    ASSERT_GE(cut, 0);
    ASSERT_LT(cut, spec.frames);
    EXPECT_EQ(sides[1].session->CutFrame(2), cut);
    const replay::ReplayFile file = CheckReplays(spec, sides, 0);
    // From the cut on, the leaver's input bytes are zero, as every survivor's game got them;
    // before it, some are not (it played).
    bool before = false;
    for (int32_t f = 0; f < file.frameCount; ++f) {
        const auto in = file.Inputs(f).subspan(2 * replay::SceneInput::kBytes, replay::SceneInput::kBytes);
        const bool zero = std::all_of(in.begin(), in.end(), [](uint8_t b) { return b == 0; });
        if (f >= cut) {
            ASSERT_TRUE(zero) << "frame " << f;
        } else if (!zero) {
            before = true;
        }
    }
    EXPECT_TRUE(before);
}

TEST(RollbackReplay, FinishRecordingEndsAtTheNewestFinalFrame) {
    replay::SceneGame scene("vertical_stack");
    TallyGame game(scene);
    auto session = RollbackSessionBuilder().Players(1).InputBytes(8).LocalPlayer(0).Build();
    const auto& info = scene.info();
    WorldGameAdapter adapter(
        scene.world(), game,
        WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                          static_cast<uint32_t>(info.positionIterations)});
    replay::MemorySink sink;
    replay::RecorderConfig config = ConfigFor(scene, 1);
    config.hashInterval = 7;  // the last frame is not on the interval: its hash is taken anyway
    replay::Recorder recorder(scene.world(), game, sink, config);
    ASSERT_TRUE(adapter.Record(recorder));
    replay::ScriptedInputs inputs(9, 1);
    std::vector<uint8_t> in;
    for (int i = 0; i < 100; ++i) {
        inputs.Next(in);
        session->AddLocalInput(0, in);
        ASSERT_TRUE(adapter.Execute(*session, session->AdvanceFrame()));
    }
    EXPECT_FALSE(adapter.Record(recorder));  // already recording, and frames were executed
    ASSERT_TRUE(adapter.FinishRecording(*session));
    EXPECT_EQ(adapter.RecordedFrames(), 100);
    replay::ReplayFile file;
    ASSERT_TRUE(replay::ParseReplay(sink.bytes(), file).ok());
    EXPECT_EQ(file.frameCount, 100);
    EXPECT_EQ(file.finalHash, scene.world().Hash());
    replay::SceneGame fresh("vertical_stack");
    TallyGame freshGame(fresh);
    replay::Player player(file, fresh.world(), freshGame);
    EXPECT_TRUE(player.Verify().ok);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
