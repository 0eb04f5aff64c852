// The lockstep codec (Protocol.h): every message round trips, encoding is canonical, and
// truncated, random or mutated datagrams are refused (or decode to something that encodes
// back to the same bytes) without reading past the buffer.

#include "lockbox/net/Protocol.h"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

const SessionShape kShape{3, 8};

std::vector<uint8_t> Bytes(size_t n, uint8_t seed) {
    std::vector<uint8_t> b(n);
    for (size_t i = 0; i < n; ++i) b[i] = static_cast<uint8_t>(seed + i * 37);
    return b;
}

// One of every message, with values that exercise wide varints and repeat runs.
std::vector<Message> AllMessages() {
    std::vector<Message> m;
    m.push_back(Hello{0x00020001u, 0xDEADBEEFu, kAnySlot, 123456789012345ull});
    m.push_back(Welcome{2, 3, 8, 60, 0, 30, 1000, 0x12345678u, true, 99, 5});
    m.push_back(Reject{RejectReason::e_full});
    Inputs in;
    in.slot = 1;
    in.firstFrame = 70000;
    in.bytes = Bytes(8 * 5, 1);
    std::fill(in.bytes.begin() + 16, in.bytes.begin() + 24, uint8_t{0});             // a zero entry
    std::copy(in.bytes.begin() + 24, in.bytes.begin() + 32, in.bytes.begin() + 32);  // a repeat
    m.push_back(in);
    m.push_back(InputAck{65536, 300});
    Confirmed c;
    c.firstFrame = 0x7FFFFFF0;
    c.bytes.assign(3 * 8 * 4, 0);
    c.bytes[5] = 9;        // frame 0 slot 0
    c.bytes[24 + 5] = 9;   // frame 1 slot 0 repeats
    c.bytes[48 + 17] = 4;  // frame 2 slot 2
    m.push_back(c);
    m.push_back(ConfirmedAck{127});
    m.push_back(Ping{0xFFFFFFFFFFFFFFFFull});
    m.push_back(Pong{1ull << 40, 17});
    m.push_back(HashReport{128, 0x0123456789ABCDEFull});
    m.push_back(KeepAlive{});
    m.push_back(Disconnect{RejectReason::e_timeout});
    m.push_back(SnapshotRequest{42});
    m.push_back(SnapshotChunk{42, 2500, 2, Bytes(2500 - 2048, 3)});
    m.push_back(SnapshotAck{42, 1});
    m.push_back(Admit{44});
    m.push_back(DesyncNotice{2147483647});
    return m;
}

std::vector<uint8_t> Encode(const Header& h, const std::vector<Message>& messages, size_t limit = 1 << 20) {
    DatagramWriter w;
    w.Begin(h);
    for (const Message& m : messages) EXPECT_TRUE(w.Add(m, kShape, limit)) << "type " << m.index() + 1;
    return {w.Bytes().begin(), w.Bytes().end()};
}

TEST(Protocol, EveryMessageRoundTripsAlone) {
    for (const Message& m : AllMessages()) {
        SCOPED_TRACE(m.index() + 1);
        const Header h{kProtocolVersion, 0xA5A5A5A5u, 65535};
        const std::vector<uint8_t> bytes = Encode(h, {m});
        Header back;
        std::vector<Message> out;
        ASSERT_EQ(DecodeDatagram(bytes, kShape, back, out), DecodeError::e_ok);
        EXPECT_EQ(back, h);
        ASSERT_EQ(out.size(), 1u);
        EXPECT_TRUE(out[0] == m);
        EXPECT_EQ(bytes.size(), kHeaderBytes + DatagramWriter::SizeOf(m, kShape));
    }
}

TEST(Protocol, ManyMessagesShareOneDatagram) {
    const std::vector<Message> all = AllMessages();
    const std::vector<uint8_t> bytes = Encode(Header{kProtocolVersion, 7, 1}, all);
    Header back;
    std::vector<Message> out;
    ASSERT_EQ(DecodeDatagram(bytes, kShape, back, out), DecodeError::e_ok);
    ASSERT_EQ(out.size(), all.size());
    for (size_t i = 0; i < all.size(); ++i) EXPECT_TRUE(out[i] == all[i]) << i;
}

TEST(Protocol, IdleInputsCostOnlyTheBitmap) {
    Inputs in;
    in.slot = 0;
    in.firstFrame = 10;
    in.bytes.assign(8 * 16, 0);
    // type, slot, frame, count, two bitmap bytes: sixteen idle frames in six bytes.
    EXPECT_EQ(DatagramWriter::SizeOf(in, kShape), 6u);
}

TEST(Protocol, OutOfRangeMessagesAreNotEncoded) {
    DatagramWriter w;
    w.Begin(Header{});
    EXPECT_FALSE(w.Add(Inputs{3, 0, Bytes(8, 0)}, kShape));                      // slot >= players
    EXPECT_FALSE(w.Add(Inputs{0, 0, Bytes(7, 0)}, kShape));                      // not a whole input
    EXPECT_FALSE(w.Add(Inputs{0, -1, Bytes(8, 0)}, kShape));                     // negative frame
    EXPECT_FALSE(w.Add(Confirmed{0, Bytes(8, 0)}, kShape));                      // not a whole row
    EXPECT_FALSE(w.Add(Welcome{3, 3, 8, 60, 0, 1, 0, 1, false, 0, 0}, kShape));  // slot >= players
    EXPECT_FALSE(w.Add(Welcome{0, 3, 8, 60, 0, 1, 0, 0, false, 0, 0}, kShape));  // token 0
    EXPECT_FALSE(w.Add(SnapshotChunk{0, 2000, 0, Bytes(999, 0)}, kShape));       // wrong length
    EXPECT_FALSE(w.Add(SnapshotChunk{0, 2000, 2, {}}, kShape));                  // past the end
    EXPECT_FALSE(w.Add(Reject{RejectReason::e_count}, kShape));
    EXPECT_FALSE(w.Add(HashReport{0, 0}, kShape, kHeaderBytes + 5));  // over the limit
    EXPECT_EQ(w.MessageCount(), 0u);
    EXPECT_EQ(w.Size(), kHeaderBytes);
}

TEST(Protocol, InputMessagesNeedTheShape) {
    const std::vector<uint8_t> bytes = Encode(Header{}, {Inputs{0, 0, Bytes(8, 1)}});
    Header h;
    std::vector<Message> out;
    EXPECT_EQ(DecodeDatagram(bytes, SessionShape{}, h, out), DecodeError::e_noShape);
    EXPECT_TRUE(out.empty());
}

TEST(Protocol, HeaderChecks) {
    std::vector<uint8_t> bytes = Encode(Header{kProtocolVersion, 9, 3}, {KeepAlive{}});
    Header h;
    std::vector<Message> out;
    std::vector<uint8_t> bad = bytes;
    bad[0] ^= 1;
    EXPECT_EQ(DecodeDatagram(bad, kShape, h, out), DecodeError::e_badMagic);
    bad = bytes;
    bad[2] = kProtocolVersion + 1;
    EXPECT_EQ(DecodeDatagram(bad, kShape, h, out), DecodeError::e_badVersion);
    EXPECT_EQ(DecodeHeader(bad, h), DecodeError::e_badVersion);
    EXPECT_EQ(h.token, 9u);  // still read, so a Reject can be addressed
    bad = bytes;
    bad.back() = 0;  // type 0
    EXPECT_EQ(DecodeDatagram(bad, kShape, h, out), DecodeError::e_badType);
    bad.back() = static_cast<uint8_t>(MessageType::e_end);
    EXPECT_EQ(DecodeDatagram(bad, kShape, h, out), DecodeError::e_badType);
    bad.resize(kHeaderBytes);
    EXPECT_EQ(DecodeDatagram(bad, kShape, h, out), DecodeError::e_tooShort);
    EXPECT_EQ(DecodeDatagram({}, kShape, h, out), DecodeError::e_tooShort);
}

TEST(Protocol, NonCanonicalSpellingsAreRefused) {
    Header h;
    std::vector<Message> out;
    // ConfirmedAck 1 spelled with two varint bytes.
    std::vector<uint8_t> bytes = Encode(Header{}, {ConfirmedAck{1}});
    bytes.back() = 0x81;
    bytes.push_back(0x00);
    EXPECT_EQ(DecodeDatagram(bytes, kShape, h, out), DecodeError::e_badVarint);
    // An eleven-byte varint.
    bytes = Encode(Header{}, {Ping{0}});
    bytes.pop_back();
    for (int i = 0; i < 10; ++i) bytes.push_back(0xFF);
    bytes.push_back(0x01);
    EXPECT_NE(DecodeDatagram(bytes, kShape, h, out), DecodeError::e_ok);
    // A frame number above INT32_MAX.
    bytes = Encode(Header{}, {Ping{0x80000000ull}});
    bytes[kHeaderBytes] = static_cast<uint8_t>(MessageType::e_admit);
    EXPECT_EQ(DecodeDatagram(bytes, kShape, h, out), DecodeError::e_badValue);
    // An explicit input equal to its repeat source (all zero on the first frame).
    bytes = Encode(Header{}, {Inputs{0, 5, Bytes(8, 1)}});
    for (size_t i = bytes.size() - 8; i < bytes.size(); ++i) bytes[i] = 0;
    EXPECT_EQ(DecodeDatagram(bytes, kShape, h, out), DecodeError::e_badValue);
}

// Every strict prefix either fails or decodes to a prefix of the messages; nothing crashes.
TEST(Protocol, TruncationAtEveryLength) {
    const std::vector<Message> all = AllMessages();
    const std::vector<uint8_t> bytes = Encode(Header{kProtocolVersion, 1, 2}, all);
    Header h;
    std::vector<Message> out;
    for (size_t n = 0; n < bytes.size(); ++n) {
        const std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
        const DecodeError e = DecodeDatagram(prefix, kShape, h, out);
        if (e != DecodeError::e_ok) {
            EXPECT_TRUE(out.empty()) << n;
            continue;
        }
        ASSERT_LT(out.size(), all.size()) << n;
        for (size_t i = 0; i < out.size(); ++i) EXPECT_TRUE(out[i] == all[i]) << n;
    }
}

// Whatever decodes encodes back to exactly the same bytes.
void ExpectCanonical(const std::vector<uint8_t>& bytes) {
    Header h;
    std::vector<Message> out;
    if (DecodeDatagram(bytes, kShape, h, out) != DecodeError::e_ok) {
        EXPECT_TRUE(out.empty());
        return;
    }
    DatagramWriter w;
    w.Begin(h);
    for (const Message& m : out) ASSERT_TRUE(w.Add(m, kShape, 1 << 20));
    EXPECT_EQ(std::vector<uint8_t>(w.Bytes().begin(), w.Bytes().end()), bytes);
}

TEST(Protocol, RandomBytesAfterAValidHeader) {
    const uint64_t seed = 0xC0FFEE;
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    DatagramWriter w;
    for (int round = 0; round < 20000; ++round) {
        w.Begin(Header{kProtocolVersion, static_cast<uint32_t>(rng()), static_cast<uint16_t>(rng())});
        std::vector<uint8_t> bytes(w.Bytes().begin(), w.Bytes().end());
        const size_t n = rng() % 64;
        // Half the time a valid type byte first, so the message bodies get exercised.
        if (n > 0 && (rng() & 1)) bytes.push_back(static_cast<uint8_t>(1 + rng() % 17));
        for (size_t i = 0; i < n; ++i) bytes.push_back(static_cast<uint8_t>(rng()));
        ExpectCanonical(bytes);
    }
}

TEST(Protocol, MutatedValidDatagrams) {
    const uint64_t seed = 0xBADC0DE;
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    const std::vector<Message> all = AllMessages();
    for (int round = 0; round < 20000; ++round) {
        std::vector<Message> pick;
        for (int k = 0; k < 3; ++k) pick.push_back(all[rng() % all.size()]);
        std::vector<uint8_t> bytes = Encode(Header{kProtocolVersion, 5, 6}, pick);
        const int flips = 1 + static_cast<int>(rng() % 3);
        for (int f = 0; f < flips; ++f) {
            const size_t at = kHeaderBytes + rng() % (bytes.size() - kHeaderBytes);
            switch (rng() % 3) {
                case 0: bytes[at] = static_cast<uint8_t>(bytes[at] ^ (1u << (rng() % 8))); break;
                case 1: bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(at)); break;
                default:
                    bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), static_cast<uint8_t>(rng()));
                    break;
            }
            if (bytes.size() <= kHeaderBytes) break;
        }
        ExpectCanonical(bytes);
    }
}

TEST(Protocol, Names) {
    EXPECT_EQ(DecodeErrorName(DecodeError::e_truncated), "truncated");
    EXPECT_EQ(RejectReasonName(RejectReason::e_full), "full");
    for (uint8_t r = 0; r < static_cast<uint8_t>(RejectReason::e_count); ++r)
        EXPECT_NE(RejectReasonName(static_cast<RejectReason>(r)), "unknown");
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
