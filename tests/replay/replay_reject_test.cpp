// Bad files are refused with an error naming the offset, chunk and frame, never a crash; a
// tampered input or stored hash gives the first divergent frame.
#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>

#include "../../replay/src/Chunks.h"
#include "ReplayTestUtil.h"
#include "lockbox/common/Bytes.h"

namespace lockbox::replay::testing {
namespace LOCKBOX_TEST_FILE {

std::vector<uint8> SmallReplay() {
    RecordOptions o;
    o.frames = 20;
    o.keyframeInterval = 10;
    return RecordScene("hello", o);
}

TEST(ReplayReject, EveryTruncationIsRefused) {
    const std::vector<uint8> bytes = SmallReplay();
    ReplayFile file;
    for (size_t n = 0; n < bytes.size(); ++n) {
        const Error e = ParseReplay(std::span<const uint8>(bytes.data(), n), file);
        ASSERT_FALSE(e.ok()) << "prefix of " << n << " bytes accepted";
        EXPECT_FALSE(e.message.empty());
        if (n >= kHeaderBytes) {
            EXPECT_TRUE(e.code == ErrorCode::e_truncated || e.code == ErrorCode::e_missing)
                << n << ": " << e.Describe();
        }
    }
    EXPECT_TRUE(ParseReplay(bytes, file).ok());
}

TEST(ReplayReject, TruncationMessageNamesOffsetChunkAndFrame) {
    const std::vector<uint8> bytes = SmallReplay();
    ReplayFile file;
    const Error e = ParseReplay(std::span<const uint8>(bytes.data(), bytes.size() - 40), file);
    ASSERT_EQ(e.code, ErrorCode::e_truncated);
    EXPECT_GT(e.offset, kHeaderBytes);
    EXPECT_GE(e.chunkIndex, 2);
    EXPECT_EQ(e.frame, 20);
    const std::string d = e.Describe();
    EXPECT_NE(d.find("truncated at offset"), std::string::npos) << d;
    EXPECT_NE(d.find("frame 20"), std::string::npos) << d;
}

TEST(ReplayReject, EveryFlippedBitIsDetected) {
    const std::vector<uint8> bytes = SmallReplay();
    ReplayFile file;
    // Every byte, one bit each (rotating), plus every bit of the header.
    for (size_t i = 0; i < bytes.size(); ++i) {
        for (int bit = 0; bit < 8; ++bit) {
            if (i >= kHeaderBytes && bit != static_cast<int>(i % 8)) continue;
            std::vector<uint8> bad = bytes;
            bad[i] ^= static_cast<uint8>(1u << bit);
            const Error e = ParseReplay(bad, file);
            ASSERT_FALSE(e.ok()) << "flip at byte " << i << " bit " << bit << " accepted";
        }
    }
}

TEST(ReplayReject, ForeignAndNewerFiles) {
    std::vector<uint8> bytes = SmallReplay();
    ReplayFile file;
    std::vector<uint8> foreign(bytes.size(), 0x42);
    EXPECT_EQ(ParseReplay(foreign, file).code, ErrorCode::e_badMagic);
    EXPECT_EQ(ParseReplay({}, file).code, ErrorCode::e_truncated);
    const uint8 hello[] = {'h', 'e', 'l', 'l', 'o'};
    EXPECT_EQ(ParseReplay(hello, file).code, ErrorCode::e_badMagic);

    // A newer format version is named as such, even with a valid checksum.
    std::vector<uint8> newer = bytes;
    newer[4] = static_cast<uint8>(kFormatVersion + 1);
    Error e = ParseReplay(newer, file);
    EXPECT_EQ(e.code, ErrorCode::e_badVersion);
    EXPECT_NE(e.message.find("newer"), std::string::npos) << e.message;

    // Another determinism version: re-encode a valid header that claims it.
    Header h;
    ASSERT_TRUE(detail::DecodeHeader(bytes, h).ok());
    h.determinismVersion ^= 0x10000u;
    std::vector<uint8> other;
    detail::EncodeHeader(h, other);
    std::copy(other.begin(), other.end(), bytes.begin());
    e = ParseReplay(bytes, file);
    EXPECT_EQ(e.code, ErrorCode::e_badEngine);
    EXPECT_NE(e.message.find("determinism"), std::string::npos);
}

TEST(ReplayReject, CorruptChunkContentsAreNamed) {
    // A well-framed INPT chunk that announces frames out of sequence.
    std::vector<uint8> bytes = SmallReplay();
    std::vector<uint8> payload;
    bytes::Writer w(payload);
    w.U32(5);
    w.U32(1);
    for (int i = 0; i < 16; ++i) w.U8(0);
    std::vector<uint8> chunk;
    detail::EncodeChunk(e_chunkInputs, payload, 0, chunk);
    bytes.insert(bytes.end() - 36, chunk.begin(), chunk.end());
    ReplayFile file;
    const Error e = ParseReplay(bytes, file);
    EXPECT_EQ(e.code, ErrorCode::e_badChunk);
    EXPECT_EQ(e.chunkType, e_chunkInputs);
    EXPECT_EQ(e.frame, 5);
    EXPECT_NE(e.Describe().find("'INPT'"), std::string::npos) << e.Describe();
}

// A file found by the fuzzer: a replay without input bytes whose input blocks announce 201
// million frames (they take no room), which the reader used to allocate hashes for (1.8 GB)
// before the END record refused the count. The frame limit refuses it first.
TEST(ReplayReject, FramesWithoutInputsCannotMakeTheReaderAllocate) {
    std::ifstream in(std::string(LOCKBOX_SOURCE_DIR) + "/tests/replay/bad/frames_without_inputs.lbr", std::ios::binary);
    ASSERT_TRUE(in.good());
    std::vector<uint8> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The file was recorded under one determinism version; it is made this engine's, so that
    // the reader goes on to the chunks whatever the version.
    Header header;
    ASSERT_TRUE(detail::DecodeHeader(bytes, header).ok());
    header.determinismVersion = b2_determinismVersion;
    std::vector<uint8> resealed;
    detail::EncodeHeader(header, resealed);
    ASSERT_EQ(resealed.size(), size_t{kHeaderBytes});
    std::copy(resealed.begin(), resealed.end(), bytes.begin());
    ReplayFile file;
    const Error e = ParseReplay(bytes, file);
    EXPECT_EQ(e.code, ErrorCode::e_badChunk);
    EXPECT_EQ(e.chunkType, e_chunkInputs);
    EXPECT_NE(e.message.find("frames would take the replay past"), std::string::npos) << e.Describe();
    EXPECT_LE(file.hashes.size(), size_t{kMaxFrames});
}

TEST(ReplayReject, CorruptSnapshotIsRefusedByThePlayer) {
    std::vector<uint8> bytes = SmallReplay();
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok());
    p.file.seed.world[p.file.seed.world.size() / 2] ^= 0x10;
    p.Rebind();
    const VerifyResult r = p.player->Verify();
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error.code, ErrorCode::e_badSnapshot);
    EXPECT_EQ(r.error.frame, 0);
}

TEST(ReplayReject, TamperedInputGivesFirstDivergentFrame) {
    RecordOptions o;
    o.frames = 80;
    const std::vector<uint8> bytes = RecordScene("vertical_stack", o);
    Playback p(bytes);
    ASSERT_TRUE(p.error.ok());
    // Player 1 of frame 41 gives the pyramid a shove the recording never had.
    const size_t at = 41 * p.file.FrameInputBytes() + SceneInput::kBytes;
    SceneInput shove;
    shove.action = e_actImpulse;
    shove.pick = 3;
    shove.a = 500;
    shove.Encode(p.file.inputs.data() + at);
    p.Rebind();
    const VerifyResult r = p.player->Verify();
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.firstBadFrame, 41);
    EXPECT_EQ(r.expected, p.file.hashes[41]);
    EXPECT_NE(r.actual, r.expected);
    EXPECT_NE(r.message.find("frame 41"), std::string::npos) << r.message;
}

TEST(ReplayReject, WrongStoredHashGivesItsFrame) {
    RecordOptions o;
    o.frames = 50;
    Playback p(RecordScene("hello", o));
    ASSERT_TRUE(p.error.ok());
    p.file.hashes[33] ^= 1;
    p.Rebind();
    const VerifyResult r = p.player->Verify();
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.firstBadFrame, 33);
    p.file.hashes[33] ^= 1;
    p.file.finalHash ^= 1;
    p.Rebind();
    EXPECT_EQ(p.player->Verify().firstBadFrame, 49);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::replay::testing
