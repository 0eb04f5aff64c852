// lockbox/common/Bytes.h: the one checked reader and the writer for untrusted bytes (snapshot
// images, replay files, datagrams). Byte order, varint spelling, and what a failed read
// leaves behind: zeros, the first error and its offset, nothing left to read.
#include "lockbox/common/Bytes.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace lockbox::bytes {
namespace LOCKBOX_TEST_FILE {

TEST(Bytes, FixedWidthFieldsAreLittleEndian) {
    std::vector<uint8_t> out;
    Writer w(out);
    w.U8(0x01);
    w.U16(0x0302);
    w.U32(0x07060504);
    w.U64(0x0F0E0D0C0B0A0908ull);
    w.I32(-2);
    w.I64(-3);
    const std::vector<uint8_t> expected = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09,
                                           0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0xFE, 0xFF, 0xFF,
                                           0xFF, 0xFD, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
    ASSERT_EQ(out, expected);

    Reader r(out);
    EXPECT_EQ(r.U8(), 0x01);
    EXPECT_EQ(r.U16(), 0x0302);
    EXPECT_EQ(r.U32(), 0x07060504u);
    EXPECT_EQ(r.U64(), 0x0F0E0D0C0B0A0908ull);
    EXPECT_EQ(r.I32(), -2);
    EXPECT_EQ(r.I64(), -3);
    EXPECT_TRUE(r.Ok());
    EXPECT_TRUE(r.AtEnd());
}

TEST(Bytes, WriterAppendsAndPatches) {
    std::vector<uint8_t> out = {0xAA};
    Writer w(out);
    EXPECT_EQ(w.Position(), 1u);
    w.U32(0);
    w.U64(0);
    w.PatchU32(1, 0x44332211);
    w.PatchU64(5, 0x8877665544332211ull);
    const std::vector<uint8_t> expected = {0xAA, 0x11, 0x22, 0x33, 0x44, 0x11, 0x22,
                                           0x33, 0x44, 0x55, 0x66, 0x77, 0x88};
    EXPECT_EQ(out, expected);
}

TEST(Bytes, VarintsAreMinimalLeb128) {
    const uint64_t values[] = {0, 1, 127, 128, 300, 16383, 16384, 0xFFFFFFFFull, UINT64_MAX};
    const size_t lengths[] = {1, 1, 1, 2, 2, 2, 3, 5, 10};
    for (size_t i = 0; i < std::size(values); ++i) {
        std::vector<uint8_t> out;
        Writer(out).Varint(values[i]);
        EXPECT_EQ(out.size(), lengths[i]) << values[i];
        Reader r(out);
        EXPECT_EQ(r.Varint(), values[i]);
        EXPECT_TRUE(r.Ok());
        EXPECT_TRUE(r.AtEnd());
    }
    std::vector<uint8_t> out;
    Writer(out).Varint(300);
    EXPECT_EQ(out, (std::vector<uint8_t>{0xAC, 0x02}));
}

TEST(Bytes, RefusesVarintsThatAreLongOrNotMinimal) {
    const std::vector<std::vector<uint8_t>> bad = {
        {0x80, 0x00},                                                        // 0 spelled in two bytes
        {0xFF, 0x80, 0x00},                                                  // a zero last byte
        {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x02},        // above 64 bits
        {0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01},  // 11 bytes
    };
    for (const auto& bytes : bad) {
        Reader r(bytes);
        EXPECT_EQ(r.Varint(), 0u);
        EXPECT_EQ(r.Error(), ReadError::e_badVarint);
        EXPECT_EQ(r.ErrorOffset(), 0u);
    }
    const std::vector<uint8_t> cut = {0x05, 0x80, 0x80};
    Reader r(cut);
    EXPECT_EQ(r.Varint(), 5u);
    EXPECT_EQ(r.Varint(), 0u);
    EXPECT_EQ(r.Error(), ReadError::e_truncated);
    EXPECT_EQ(r.ErrorOffset(), 1u);
}

TEST(Bytes, FirstFailureSticksWithItsOffset) {
    const std::vector<uint8_t> in = {1, 2, 3, 4, 5, 6};
    Reader r(in);
    EXPECT_EQ(r.U32(), 0x04030201u);
    EXPECT_EQ(r.U32(), 0u);  // two bytes left
    EXPECT_FALSE(r.Ok());
    EXPECT_EQ(r.Error(), ReadError::e_truncated);
    EXPECT_EQ(r.ErrorOffset(), 4u);
    EXPECT_EQ(r.Position(), 4u);
    // Nothing is left once failed, not even the two bytes that would fit a u16.
    EXPECT_EQ(r.Remaining(), 0u);
    EXPECT_EQ(r.U16(), 0u);
    EXPECT_TRUE(r.Bytes(1).empty());
    r.Refuse();
    EXPECT_EQ(r.Error(), ReadError::e_truncated);
    EXPECT_EQ(r.ErrorOffset(), 4u);
}

TEST(Bytes, RefuseStopsTheReaderWhereTheParserIs) {
    const std::vector<uint8_t> in = {9, 1, 2};
    Reader r(in);
    EXPECT_EQ(r.U8(), 9);
    r.Refuse();
    EXPECT_EQ(r.Error(), ReadError::e_refused);
    EXPECT_EQ(r.ErrorOffset(), 1u);
    EXPECT_EQ(r.U8(), 0);
}

TEST(Bytes, BlobsViewsCopiesAndPeeks) {
    std::vector<uint8_t> out;
    Writer w(out);
    const std::vector<uint8_t> payload = {7, 8, 9};
    w.Blob(payload);
    w.Blob({});
    w.U8(42);
    EXPECT_EQ(out.size(), 4u + 3u + 4u + 1u);

    Reader r(out);
    const auto blob = r.Blob();
    EXPECT_EQ(std::vector<uint8_t>(blob.begin(), blob.end()), payload);
    EXPECT_EQ(blob.data(), out.data() + 4);  // a view, not a copy
    EXPECT_TRUE(r.Blob().empty());
    EXPECT_EQ(r.Peek(1).size(), 1u);
    EXPECT_EQ(r.Position(), 11u);
    uint8_t last = 0;
    EXPECT_TRUE(r.Copy({&last, 1}));
    EXPECT_EQ(last, 42);
    EXPECT_TRUE(r.Ok());
    EXPECT_FALSE(r.Copy({&last, 1}));
    EXPECT_EQ(r.Error(), ReadError::e_truncated);

    // A blob announcing more bytes than follow.
    const std::vector<uint8_t> lying = {5, 0, 0, 0, 1, 2};
    Reader l(lying);
    EXPECT_TRUE(l.Blob().empty());
    EXPECT_EQ(l.Error(), ReadError::e_truncated);
    EXPECT_EQ(l.ErrorOffset(), 4u);
}

TEST(Bytes, StartOffsetAndSkip) {
    const std::vector<uint8_t> in = {0, 0, 0x34, 0x12, 0xFF};
    Reader r(in, 2);
    EXPECT_EQ(r.U16(), 0x1234);
    r.Skip(1);
    EXPECT_TRUE(r.AtEnd());
    EXPECT_TRUE(r.Ok());
    r.Skip(1);
    EXPECT_EQ(r.Error(), ReadError::e_truncated);
    EXPECT_EQ(r.ErrorOffset(), 5u);

    Reader past(in, 99);  // clamped to the end
    EXPECT_EQ(past.Position(), in.size());
    EXPECT_EQ(past.U8(), 0);
    EXPECT_FALSE(past.Ok());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::bytes
