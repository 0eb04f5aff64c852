// Record then verify: scenes with spawning and joints, files on disk, seeking, hash intervals,
// and an older reader skipping a chunk type it does not know.
#include <cstdio>
#include <string>

#include "../../replay/src/Chunks.h"
#include "ReplayTestUtil.h"

namespace lockbox::replay::testing {
namespace LOCKBOX_TEST_FILE {

class RecordVerify : public ::testing::TestWithParam<const char*> {};

TEST_P(RecordVerify, VerifiesAndMatchesRecordedHashes) {
    RecordOptions o;
    o.frames = 90;
    std::vector<uint64> hashes;
    const std::vector<uint8> bytes = RecordScene(GetParam(), o, &hashes);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok()) << p.error.Describe();
    EXPECT_EQ(p.file.frameCount, o.frames);
    EXPECT_EQ(p.file.keyframes.size(), 3u);  // frames 30, 60, 90
    for (int32 f = 0; f < o.frames; ++f)
        EXPECT_EQ(p.file.hashes[static_cast<size_t>(f)], hashes[static_cast<size_t>(f)]);
    const VerifyResult r = p.player->Verify();
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.frames, o.frames);
    EXPECT_EQ(r.hashesChecked, o.frames);
    EXPECT_EQ(r.finalHash, hashes.back());
}

// hello (plain), rain (bodies spawned by the scene), car, ragdolls and pulley_gear (joints),
// one_sided_platform (a contact listener), bullet_wall_bullet (continuous collision).
INSTANTIATE_TEST_SUITE_P(Scenes, RecordVerify,
                         ::testing::Values("hello", "rain", "car", "ragdolls", "pulley_gear", "one_sided_platform",
                                           "bullet_wall_bullet", "pendulum"));

TEST(Replay, ScriptedInputsSpawnAndDestroyBodies) {
    RecordOptions o;
    o.frames = 240;
    o.players = 4;
    const std::vector<uint8> bytes = RecordScene("hello", o);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok());
    int spawns = 0, destroys = 0;
    for (int32 f = 0; f < p.file.frameCount; ++f) {
        const auto in = p.file.Inputs(f);
        for (size_t at = 0; at < in.size(); at += SceneInput::kBytes) {
            spawns += in[at] == e_actSpawnBox || in[at] == e_actSpawnCircle;
            destroys += in[at] == e_actDestroy;
        }
    }
    EXPECT_GT(spawns, 0);
    EXPECT_GT(destroys, 0);
    EXPECT_TRUE(p.player->Verify().ok);
}

TEST(Replay, FileRoundTripAndSameBytesTwice) {
    const std::string path = ::testing::TempDir() + "replay_roundtrip.lbr";
    {
        SceneGame game("vertical_stack");
        FileSink sink(path);
        ASSERT_TRUE(sink.ok());
        Recorder rec(game.world(), game, sink, game.Config(2));
        ASSERT_TRUE(rec.Begin().ok());
        ScriptedInputs script(5, 2);
        std::vector<uint8> in;
        for (int f = 0; f < 60; ++f) {
            script.Next(in);
            rec.Advance(in);
        }
        ASSERT_TRUE(rec.Finish().ok());
        ASSERT_TRUE(sink.Close());
    }
    ReplayFile file;
    ASSERT_TRUE(LoadReplay(path, file).ok());
    SceneGame game("vertical_stack");
    Player player(file, game.world(), game);
    EXPECT_TRUE(player.Verify().ok);
    // Recording is deterministic down to the bytes of the file.
    std::vector<uint8> bytes;
    ASSERT_TRUE(ReadFileBytes(path, bytes).ok());
    RecordOptions o;
    o.frames = 60;
    o.seed = 5;
    o.keyframeInterval = 600;
    EXPECT_EQ(bytes, RecordScene("vertical_stack", o));
    std::remove(path.c_str());
}

TEST(Replay, ConfirmedFramesFromASessionGiveTheSameFile) {
    RecordOptions o;
    o.frames = 70;
    o.keyframeInterval = 30;
    const std::vector<uint8> expected = RecordScene("rain", o);
    // A session steps its own world and hands the recorder each confirmed frame.
    SceneGame game("rain");
    MemorySink sink;
    RecorderConfig config = game.Config(o.players);
    config.keyframeInterval = o.keyframeInterval;
    Recorder recorder(game.world(), game, sink, config);
    ASSERT_TRUE(recorder.Begin().ok());
    ScriptedInputs script(o.seed, o.players);
    std::vector<uint8> inputs;
    const auto& info = game.info();
    for (int32 f = 0; f < o.frames; ++f) {
        script.Next(inputs);
        game.Apply(game.world(), f, inputs);
        game.world().Step(scenes::LockboxEngine::TimeStep(info.hz), info.velocityIterations, info.positionIterations);
        recorder.AppendConfirmed(inputs, game.world().Hash(), &game.world());
    }
    ASSERT_TRUE(recorder.Finish().ok());
    EXPECT_EQ(sink.bytes(), expected);
}

TEST(Replay, SeekThroughKeyframesEqualsStraightPlay) {
    RecordOptions o;
    o.frames = 100;
    o.keyframeInterval = 25;
    std::vector<uint64> hashes;
    const std::vector<uint8> bytes = RecordScene("rain", o, &hashes);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok());
    for (int32 target : {77, 25, 3, 100, 50, 51}) {
        ASSERT_TRUE(p.player->Seek(target).ok());
        EXPECT_EQ(p.player->Frame(), target);
        const uint64 expected = target == 0 ? p.file.seed.hash : hashes[static_cast<size_t>(target - 1)];
        EXPECT_EQ(p.game->world().Hash(), expected) << "frame " << target;
    }
    // Seeking from 51 to 77 restored the keyframe at 75 and stepped two frames.
    const int32 restores = p.player->Restores();
    ASSERT_TRUE(p.player->Seek(77).ok());
    EXPECT_EQ(p.player->Restores(), restores + 1);
    EXPECT_EQ(p.game->world().Hash(), hashes[76]);
    EXPECT_FALSE(p.player->Seek(101).ok());
}

TEST(Replay, SparseHashesAndNoCompression) {
    RecordOptions o;
    o.frames = 61;
    o.hashInterval = 10;
    o.keyframeInterval = 0;
    o.compressionLevel = 0;
    const std::vector<uint8> bytes = RecordScene("vertical_stack", o);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok()) << p.error.Describe();
    EXPECT_TRUE(p.file.keyframes.empty());
    EXPECT_TRUE(p.file.HasHash(9));
    EXPECT_FALSE(p.file.HasHash(10));
    EXPECT_TRUE(p.file.HasHash(59));
    const VerifyResult r = p.player->Verify();
    EXPECT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.hashesChecked, 6);
}

TEST(Replay, OlderReaderSkipsUnknownChunkTypes) {
    RecordOptions o;
    o.frames = 40;
    std::vector<uint8> bytes = RecordScene("hello", o);
    // Splice a chunk of a future type right after the header and another before END.
    std::vector<uint8> future;
    const std::vector<uint8> payload(100, 0xAB);
    detail::EncodeChunk(ChunkTag('N', 'E', 'W', '!'), payload, 3, future);
    uint64 afterMeta = kHeaderBytes;
    detail::RawChunk chunk;
    std::vector<uint8> scratch;
    ASSERT_TRUE(detail::ReadChunk(bytes, afterMeta, 0, chunk, scratch).ok());
    ASSERT_EQ(chunk.type, e_chunkMeta);
    bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(afterMeta), future.begin(), future.end());
    // A second one in the middle of the file, after the first keyframe.
    bytes.insert(bytes.end() - 36 /* END record */, future.begin(), future.end());
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok()) << p.error.Describe();
    EXPECT_EQ(p.file.unknownChunks, 2u);
    EXPECT_TRUE(p.player->Verify().ok);
}

TEST(Replay, StageHashesRecordedAndReplayed) {
    RecordOptions o;
    o.frames = 30;
    o.stageHashes = true;
    const std::vector<uint8> bytes = RecordScene("bullet_stack_bullet", o);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok());
    ASSERT_EQ(p.file.stageHashes.size(), 30u * kStagesPerFrame);
    ASSERT_TRUE(p.player->Reset().ok());
    p.player->SetStageHashing(true);
    for (int32 f = 0; f < 30; ++f) {
        p.player->Step();
        for (uint32 s = 0; s < kStagesPerFrame; ++s)
            ASSERT_EQ(p.player->LastStages()[s], p.file.Stages(f)[s]) << "frame " << f << " stage " << StageName(s);
    }
    EXPECT_EQ(p.game->world().Hash(), p.file.finalHash);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay::testing
