// The rollback codec (RollbackProtocol.h): round trips, canonical encoding, and refusal of
// every truncation and malformed field.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/Transport.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

const RollbackShape kShape{3, 4};

std::vector<RollbackMessage> Sample() {
    std::vector<RollbackMessage> m;
    m.push_back(RbInputs{2, 1000, {1, 2, 3, 4, 1, 2, 3, 4, 0, 0, 0, 0, 9, 9, 9, 9}});
    m.push_back(RbInputAck{1, 77});
    m.push_back(RbQuality{4000, -2500, 123456789});
    m.push_back(RbQuality{1, INT32_MIN, 0});
    m.push_back(RbQuality{2, INT32_MAX, UINT64_MAX, 255});
    m.push_back(RbQualityReply{99, 12});
    m.push_back(RbHash{30, 0xDEADBEEFCAFEF00Dull});
    std::vector<uint8_t> rows(2 * 3 * 4, 0);
    rows[5] = 7;
    rows[17] = 7;
    m.push_back(RbConfirmed{5, rows});
    m.push_back(RbConfirmedAck{7});
    m.push_back(RbKeepAlive{});
    m.push_back(RbDisconnect{});
    m.push_back(RbJoinRequest{3});
    std::vector<uint8_t> payload(100);
    for (size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<uint8_t>(i * 7);
    m.push_back(RbSnapshotChunk{12, 100, 0x0123456789ABCDEFull, 0, payload});
    // The last, short chunk of a 1030-byte snapshot.
    m.push_back(RbSnapshotChunk{13, kRbSnapshotChunkBytes + 6, 5, 1, {1, 2, 3, 4, 5, 6}});
    m.push_back(RbSnapshotAck{12, 0});
    m.push_back(RbSnapshotAck{400, 16383});
    m.push_back(RbView{{1000, 1003, 998}});
    m.push_back(RbView{{0, 0, 0}});
    m.push_back(RbView{{INT32_MAX, 0, 5}});
    m.push_back(RbFrozen{2, 123});
    m.push_back(RbFrozen{0, 0});
    m.push_back(RbHello{0xFEDC0001u, static_cast<uint8_t>(kShape.players), kShape.inputBytes});
    m.push_back(RbDelayWish{0});
    m.push_back(RbDelayWish{kRollbackMaxInputDelay});
    return m;
}

std::vector<uint8_t> Encode(const std::vector<RollbackMessage>& msgs, uint32_t matchId = 42) {
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{kRollbackProtocolVersion, matchId});
    for (const auto& m : msgs) EXPECT_TRUE(w.Add(m, kShape));
    return {w.Bytes().begin(), w.Bytes().end()};
}

TEST(RollbackWire, RoundTripIsCanonical) {
    const auto msgs = Sample();
    const auto bytes = Encode(msgs);
    RollbackHeader h;
    std::vector<RollbackMessage> out;
    ASSERT_EQ(DecodeRollbackDatagram(bytes, kShape, h, out), DecodeError::e_ok);
    EXPECT_EQ(h.matchId, 42u);
    EXPECT_EQ(out, msgs);
    EXPECT_EQ(Encode(out), bytes);
}

TEST(RollbackWire, EveryTruncationIsRefused) {
    const auto bytes = Encode(Sample());
    RollbackHeader h;
    std::vector<RollbackMessage> out;
    // Cutting inside a message must fail; cutting exactly between messages is a shorter
    // valid datagram, so count only the failures and check no decode reads past the end.
    size_t refused = 0;
    for (size_t n = 0; n < bytes.size(); ++n) {
        const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
        if (DecodeRollbackDatagram(cut, kShape, h, out) != DecodeError::e_ok) {
            ++refused;
            EXPECT_TRUE(out.empty());
        }
    }
    EXPECT_GT(refused, bytes.size() / 2);
}

TEST(RollbackWire, MalformedFieldsAreRefused) {
    RollbackHeader h;
    std::vector<RollbackMessage> out;
    auto bytes = Encode({RbKeepAlive{}});
    auto bad = bytes;
    bad[0] ^= 1;
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badMagic);
    bad = bytes;
    bad[2] = 9;
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badVersion);
    bad = bytes;
    bad.back() = 0;
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badType);
    bad.back() = static_cast<uint8_t>(RollbackMessageType::e_end);
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badType);
    // A player beyond the shape.
    bytes = Encode({RbInputAck{2, 1}});
    bytes[kRollbackHeaderBytes + 1] = 3;
    EXPECT_EQ(DecodeRollbackDatagram(bytes, kShape, h, out), DecodeError::e_badValue);
    // A run of zero frames.
    bytes = Encode({RbInputs{0, 0, {1, 1, 1, 1}}});
    bytes[kRollbackHeaderBytes + 3] = 0;
    EXPECT_NE(DecodeRollbackDatagram(bytes, kShape, h, out), DecodeError::e_ok);
    // Inputs without a shape.
    bytes = Encode({RbInputs{0, 0, {1, 1, 1, 1}}});
    EXPECT_EQ(DecodeRollbackDatagram(bytes, RollbackShape{}, h, out), DecodeError::e_noShape);
    // Out-of-range messages are not encoded.
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{});
    EXPECT_FALSE(w.Add(RbInputs{3, 0, {1, 1, 1, 1}}, kShape));
    EXPECT_FALSE(w.Add(RbInputs{0, -1, {1, 1, 1, 1}}, kShape));
    EXPECT_FALSE(w.Add(RbInputs{0, 0, {1, 1, 1}}, kShape));
    EXPECT_FALSE(w.Add(RbInputs{0, 0, std::vector<uint8_t>(4 * (kRollbackMaxRun + 1), 1)}, kShape));
    EXPECT_FALSE(w.Add(RbHash{-1, 0}, kShape));
    EXPECT_EQ(w.MessageCount(), 0u);
}

// Version 3's agreement messages: a view has exactly one entry per player, its base is the
// smallest entry (so the encoding is unique), no entry passes INT32_MAX; a frozen value
// names a player of the match.
TEST(RollbackWire, ViewAndFrozenAreStrict) {
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{});
    EXPECT_FALSE(w.Add(RbView{{1, 2}}, kShape));              // two entries for three players
    EXPECT_FALSE(w.Add(RbView{{1, 2, 3, 4}}, kShape));        // four
    EXPECT_FALSE(w.Add(RbView{{1, -1, 3}}, kShape));          // negative
    EXPECT_FALSE(w.Add(RbView{{1, 2, 3}}, RollbackShape{}));  // no shape
    EXPECT_FALSE(w.Add(RbFrozen{3, 1}, kShape));              // no such player
    EXPECT_FALSE(w.Add(RbFrozen{0, -1}, kShape));
    EXPECT_FALSE(w.Add(RbDelayWish{kRollbackMaxInputDelay + 1}, kShape));
    EXPECT_EQ(w.MessageCount(), 0u);

    RollbackHeader h;
    std::vector<RollbackMessage> out;
    // type, base 10, deltas 0 2 1.
    auto bytes = Encode({RbView{{10, 12, 11}}});
    ASSERT_EQ(bytes.size(), kRollbackHeaderBytes + 5);
    ASSERT_EQ(DecodeRollbackDatagram(bytes, kShape, h, out), DecodeError::e_ok);
    auto bad = bytes;
    bad[kRollbackHeaderBytes + 2] = 1;  // deltas 1 2 1: the base is not the smallest entry
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badValue);
    EXPECT_TRUE(out.empty());
    bad = bytes;
    bad.pop_back();  // one entry short
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_truncated);
    // base INT32_MAX and a delta of 1: past a frame number.
    bytes = Encode({RbView{{INT32_MAX, INT32_MAX, INT32_MAX}}});
    bad = bytes;
    bad[bad.size() - 1] = 1;
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badValue);
    // A view with the decoder's shape of another player count is refused or misread, never
    // read past the end: with 4 players the 3-entry view is one entry short.
    bytes = Encode({RbView{{10, 12, 11}}});
    EXPECT_NE(DecodeRollbackDatagram(bytes, RollbackShape{4, 4}, h, out), DecodeError::e_ok);
    bytes = Encode({RbFrozen{2, 7}});
    bad = bytes;
    bad[kRollbackHeaderBytes + 1] = 3;  // player 3 of 3
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badValue);
    EXPECT_EQ(DecodeRollbackDatagram(bytes, RollbackShape{}, h, out), DecodeError::e_noShape);
    bytes = Encode({RbDelayWish{3}});
    bad = bytes;
    bad[kRollbackHeaderBytes + 1] = kRollbackMaxInputDelay + 1;
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badValue);
    // A version-2 datagram (before the agreement) is refused by its header.
    bad = bytes;
    bad[2] = 2;
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badVersion);
}

// An 8-player peer's agreement messages at their largest (every entry a 5-byte varint, all
// seven remote players frozen) take under 100 bytes: the rest of the datagram is left for
// inputs.
TEST(RollbackWire, AgreementFitsBesideTheInputs) {
    const RollbackShape eight{8, 64};
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{});
    ASSERT_TRUE(w.Add(RbView{{0, INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX}}, eight));
    for (uint8_t p = 1; p < 8; ++p) ASSERT_TRUE(w.Add(RbFrozen{p, INT32_MAX}, eight));
    EXPECT_LE(w.Size(), kRollbackHeaderBytes + 42 + 7 * 7);
    EXPECT_LE(w.Size(), Transport::kMaxDatagram / 10);
}

// Late-join messages: every chunk's payload length follows from its size and index, and
// anything inconsistent is neither encoded nor decoded.
TEST(RollbackWire, SnapshotMessagesAreBoundsChecked) {
    RollbackDatagramWriter w;
    w.Begin(RollbackHeader{});
    const std::vector<uint8_t> full(kRbSnapshotChunkBytes, 1);
    EXPECT_TRUE(w.Add(RbSnapshotChunk{0, 5000, 0, 0, full}, kShape));
    w.Begin(RollbackHeader{});
    EXPECT_FALSE(w.Add(RbSnapshotChunk{0, 5000, 0, 0, {1, 2}}, kShape));  // payload too short
    EXPECT_FALSE(w.Add(RbSnapshotChunk{0, 5000, 0, 5, {1, 2}}, kShape));  // index past the end
    EXPECT_FALSE(w.Add(RbSnapshotChunk{0, 0, 0, 0, {}}, kShape));         // empty snapshot
    EXPECT_FALSE(w.Add(RbSnapshotChunk{-1, 2, 0, 0, {1, 2}}, kShape));    // negative frame
    EXPECT_FALSE(w.Add(RbSnapshotChunk{0, kRbMaxSnapshotBytes + 1, 0, 0, full}, kShape));
    EXPECT_FALSE(w.Add(RbSnapshotAck{0, kRbMaxSnapshotBytes / kRbSnapshotChunkBytes}, kShape));
    EXPECT_FALSE(w.Add(RbJoinRequest{0}, kShape));
    EXPECT_EQ(w.MessageCount(), 0u);
    // A full chunk datagram stays well under the 1200-byte budget.
    w.Begin(RollbackHeader{});
    ASSERT_TRUE(w.Add(RbSnapshotChunk{INT32_MAX, kRbMaxSnapshotBytes, UINT64_MAX, 16383, full}, kShape));
    EXPECT_LE(w.Size(), 1100u);

    RollbackHeader h;
    std::vector<RollbackMessage> out;
    // type, frame 5 (1 byte), size 1030 (2 bytes), checksum (8), index 1 (1), 6 payload bytes.
    auto bytes = Encode({RbSnapshotChunk{5, kRbSnapshotChunkBytes + 6, 9, 1, {1, 2, 3, 4, 5, 6}}});
    ASSERT_EQ(bytes.size(), kRollbackHeaderBytes + 19);
    auto bad = bytes;
    bad[kRollbackHeaderBytes + 12] = 2;  // index 2 of a 2-chunk snapshot
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badValue);
    bad = bytes;
    bad.pop_back();  // payload one byte short
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_truncated);
    bad = bytes;
    bad.push_back(0);  // one byte too many: read as a type byte 0
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badType);
    bad = Encode({RbJoinRequest{1}});
    bad[kRollbackHeaderBytes + 1] = 0;  // attempt 0
    EXPECT_EQ(DecodeRollbackDatagram(bad, kShape, h, out), DecodeError::e_badValue);
    EXPECT_TRUE(out.empty());
}

TEST(RollbackWire, RandomBytesNeverCrash) {
    uint64_t r = 0x5eed;
    RollbackHeader h;
    std::vector<RollbackMessage> out;
    const auto good = Encode(Sample());
    size_t accepted = 0;
    for (int i = 0; i < 20000; ++i) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        std::vector<uint8_t> bytes = good;
        // Flip one to three bytes of a valid datagram.
        for (int k = 0; k < 1 + static_cast<int>((r >> 62) % 3); ++k) {
            r = r * 6364136223846793005ull + 1442695040888963407ull;
            bytes[(r >> 33) % bytes.size()] = static_cast<uint8_t>(r >> 17);
        }
        if (DecodeRollbackDatagram(bytes, kShape, h, out) == DecodeError::e_ok) {
            ++accepted;
            // Whatever is accepted re-encodes to the same bytes.
            RollbackDatagramWriter w;
            w.Begin(h);
            for (const auto& m : out) ASSERT_TRUE(w.Add(m, kShape, 1 << 20));
            EXPECT_EQ(std::vector<uint8_t>(w.Bytes().begin(), w.Bytes().end()), bytes);
        }
    }
    EXPECT_LT(accepted, 20000u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
