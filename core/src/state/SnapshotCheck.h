#pragma once
// Internal to the snapshot reader: how a check failure travels (an exception caught in
// ParseSnapshot and turned into a b2RestoreResult), how messages name values, and the reader
// the parser takes the image's fields from.

#include <array>
#include <cstdio>
#include <span>
#include <string>

#include "ByteCursor.h"
#include "SnapshotFormat.h"
#include "lockbox/common/Bytes.h"
#include "lockbox/fixed/Math.h"
#include "lockbox/state/Snapshot.h"

namespace lockbox::state_detail {

struct Image;

/// A refused image: the error and a message naming the field.
struct SnapshotFailure {
    b2SnapshotError error;
    std::string message;
};

[[noreturn]] inline void Fail(b2SnapshotError error, std::string message) {
    throw SnapshotFailure{error, std::move(message)};
}

/// The failure half of Check, kept out of line: building the message is the cold path.
[[noreturn, gnu::noinline, gnu::cold]] inline void FailCheck(const char* what, const char* problem, int64_t value) {
    Fail(b2SnapshotError::e_corrupt, std::string(what) + ": " + problem + " (value " + std::to_string(value) + ")");
}

/// Fails with e_corrupt "what: problem (value V)" unless ok. Inlined: a restore runs about
/// 30,000 of these for 1,000 bodies, and a call each cost as much as the reads they guard.
[[gnu::always_inline]] inline void Check(bool ok, const char* what, const char* problem, int64_t value) {
    if (!ok) [[unlikely]]
        FailCheck(what, problem, value);
}

/// The parser's reader: lockbox::bytes::Reader over the image, whose read past the end fails
/// the parse with e_truncated naming the offset. A record whose room is checked once is read
/// through Begin/End and the unchecked ReadCursor (ByteCursor.h), as the apply reads it again.
class ImageReader {
public:
    ImageReader(std::span<const uint8> image, size_t start) noexcept : m_in(image, start), m_data(image.data()) {}

    uint8 U8() { return Need(1).U8(); }
    uint16 U16() { return Need(2).U16(); }
    uint32 U32() { return Need(4).U32(); }
    uint64 U64() { return Need(8).U64(); }
    int32 I32() { return Need(4).I32(); }
    int64_t I64() { return Need(8).I64(); }
    Fixed F() { return Fixed::FromRaw(I32()); }
    Wide W() { return Wide::FromRaw(I64()); }
    b2Vec2 V() {
        const Fixed x = F();
        return b2Vec2(x, F());
    }

    /// A cursor over the next `bytes` bytes (e_truncated when fewer are left); hand it back to
    /// End.
    ReadCursor Begin(size_t bytes) {
        Need(bytes);
        return ReadCursor(m_data + m_in.Position());
    }
    /// Moves past the bytes a cursor from Begin read.
    void End(const ReadCursor& c) noexcept { m_in.Skip(static_cast<size_t>(c.Position() - m_data) - m_in.Position()); }

    /// Offset of the next field from the image's first byte.
    size_t Position() const noexcept { return m_in.Position(); }
    size_t Remaining() const noexcept { return m_in.Remaining(); }

private:
    /// The byte reader, once `bytes` are known to be left: its own check of the same room then
    /// folds into this one.
    bytes::Reader& Need(size_t bytes) {
        if (m_in.Remaining() < bytes) [[unlikely]]
            Truncated(bytes);
        return m_in;
    }
    [[noreturn, gnu::noinline, gnu::cold]] void Truncated(size_t bytes) const {
        Fail(b2SnapshotError::e_truncated, "the image ends inside a field: " + std::to_string(bytes) +
                                               " bytes wanted at byte " + std::to_string(m_in.Position()) + ", " +
                                               std::to_string(m_in.Remaining()) + " left");
    }

    bytes::Reader m_in;
    const uint8* m_data;
};

/// A boolean field: 0 or 1, anything else is corrupt.
template <class R>
bool ReadBool(R& r, const char* what) {
    const uint8 b = r.U8();
    Check(b <= 1, what, "is not 0 or 1", b);
    return b != 0;
}

inline std::string Hex(uint64 v) {
    char text[24];
    std::snprintf(text, sizeof text, "0x%llx", static_cast<unsigned long long>(v));
    return text;
}

/// The header fields the readers use once ReadHeader has checked the rest.
struct HeaderFields {
    uint16 format = 0;    ///< b2_snapshotFormatVersion, or an older one this build reads
    uint64 payload = 0;   ///< bytes after the header (equal to the bytes present)
    uint64 checksum = 0;  ///< the header's payload checksum (not verified by ReadHeader)
};

/// Checks an image's header (SnapshotHeader.cpp): length, endianness flag, magic, format
/// version (the current one or b2_snapshotOldestReadable on), determinism version, and the
/// announced payload length against the bytes present. Fails (throws SnapshotFailure) naming
/// the first problem.
HeaderFields ReadHeader(std::span<const uint8> bytes);

/// The sections' contents (without their tag and length), in image order; an image of format
/// 1 has no joint-reaction section (its span is empty).
using SectionSpans = std::array<std::span<const uint8>, kSectionCount>;

/// Checks the framing of an image whose header ReadHeader accepted: the sections of its
/// format with the tags 1, 2, ... in order, each length within the image, nothing after the
/// last. Fails naming the section.
SectionSpans FrameSections(std::span<const uint8> bytes, uint16 format);

/// Cross-reference checks of a parsed image (SnapshotValidate.cpp): ids, lists, the tree.
void ValidateImage(Image& image);

}  // namespace lockbox::state_detail
