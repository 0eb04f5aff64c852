#pragma once
// Internal to the snapshot reader: how a check failure travels (an exception caught in
// ParseSnapshot and turned into a b2RestoreResult) and how messages name values.

#include <cstdio>
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
    if (!ok) [[unlikely]] FailCheck(what, problem, value);
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

/// Cross-reference checks of a parsed image (SnapshotValidate.cpp): ids, lists, the tree.
void ValidateImage(Image& image);

}  // namespace lockbox::state_detail
