#pragma once
// The lockstep and rollback codecs' reader (Protocol.cpp, ProtocolMessages.cpp,
// RollbackWire.cpp): lockbox's checked byte reader (lockbox/common/Bytes.h) with the codec's
// DecodeError, plus the repeat-bitmap input runs. Writing needs nothing beyond
// lockbox::bytes::Writer.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/common/Bytes.h"
#include "lockbox/net/Protocol.h"

namespace lockbox::net::wire {

/// A bytes::Reader that also names the codec's own refusals: after the first error every read
/// returns 0 and Failure() says why.
class Reader : public bytes::Reader {
public:
    using bytes::Reader::Reader;

    /// The first error: the refusal given to Fail, or the byte reader's own failure.
    DecodeError Failure() const noexcept {
        if (m_error != DecodeError::e_ok) return m_error;
        switch (Error()) {
            case bytes::ReadError::e_none: return DecodeError::e_ok;
            case bytes::ReadError::e_truncated: return DecodeError::e_truncated;
            case bytes::ReadError::e_badVarint: return DecodeError::e_badVarint;
            case bytes::ReadError::e_refused: break;  // only through Fail, which sets m_error
        }
        return DecodeError::e_badValue;
    }
    /// Refuses what was read with `e` (kept only when nothing failed before).
    void Fail(DecodeError e) noexcept {
        if (!Ok()) return;
        m_error = e;
        Refuse();
    }

    /// A varint that must be a frame number (0 .. INT32_MAX).
    int32_t Frame() noexcept {
        const uint64_t v = Varint();
        if (v > 0x7FFFFFFFull) {
            Fail(DecodeError::e_badValue);
            return 0;
        }
        return static_cast<int32_t>(v);
    }

private:
    DecodeError m_error = DecodeError::e_ok;
};

/// Writes `entries` entries of `width` bytes with the repeat bitmap: bit i (LSB first) set
/// when entry i equals its repeat source, entry i - stride (the same player one frame
/// earlier), or all zeros for i < stride; only the entries not marked follow the bitmap.
void WriteRun(bytes::Writer& w, std::span<const uint8_t> bytes, size_t entries, size_t width, size_t stride);
/// Reads what WriteRun wrote into `out` (resized to entries * width). Refuses a non-zero
/// padding bit and an explicit entry equal to its repeat source (so the encoding stays
/// canonical).
void ReadRun(Reader& r, std::vector<uint8_t>& out, size_t entries, size_t width, size_t stride);

}  // namespace lockbox::net::wire
