#pragma once
// Internal to the snapshot reader: how a check failure travels (an exception caught in
// ParseSnapshot and turned into a b2RestoreResult) and how messages name values.

#include <array>
#include <cstdio>
#include <span>
#include <string>

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
using SectionSpans = std::array<std::span<const uint8>, 7>;

/// Checks the framing of an image whose header ReadHeader accepted: the sections of its
/// format with the tags 1, 2, ... in order, each length within the image, nothing after the
/// last. Fails naming the section.
SectionSpans FrameSections(std::span<const uint8> bytes, uint16 format);

/// Cross-reference checks of a parsed image (SnapshotValidate.cpp): ids, lists, the tree.
void ValidateImage(Image& image);

}  // namespace lockbox::state_detail
