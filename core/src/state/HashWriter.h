#pragma once
// Internal to the state hash: a little-endian field writer in front of an XXH3-64 stream.
// Every value goes through an explicit width so the byte stream is the same on every
// platform (docs/determinism.md, "State hash"). Hot records go through Begin/End (one room
// check per record, then an unchecked ByteCursor); the bytes are those of the field calls.

#include <cstddef>
#include <cstdint>

#include "ByteCursor.h"
#include "FastXxh3.h"
#include "lockbox/fixed/Assert.h"
#include "lockbox/fixed/Math.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox {

namespace state_detail {

/// Streams little-endian fixed-width fields into XXH3-64. Not copyable (owns the state).
class HashWriter {
public:
    /// The largest record Begin accepts (bytes).
    static constexpr size_t kMaxRecord = 1024;

    HashWriter() noexcept { XXH3_64bits_reset(&m_state); }
    HashWriter(const HashWriter&) = delete;
    HashWriter& operator=(const HashWriter&) = delete;

    /// A cursor with room for `maxBytes` (at most kMaxRecord); hand it back to End.
    ByteCursor Begin(size_t maxBytes) noexcept {
        LOCKBOX_ASSERT(maxBytes <= kMaxRecord, "HashWriter: a record larger than kMaxRecord");
        if (m_used + maxBytes > kBuffer) Flush();
        return ByteCursor(m_buffer + m_used);
    }
    /// Takes the bytes a cursor from Begin wrote.
    void End(const ByteCursor& c) noexcept { m_used = static_cast<size_t>(c.Position() - m_buffer); }

    void U8(uint32_t v) noexcept {
        One([&](ByteCursor& c) { c.U8(v); });
    }
    void U16(uint32_t v) noexcept {
        One([&](ByteCursor& c) { c.U16(v); });
    }
    void U32(uint32_t v) noexcept {
        One([&](ByteCursor& c) { c.U32(v); });
    }
    void U64(uint64_t v) noexcept {
        One([&](ByteCursor& c) { c.U64(v); });
    }
    /// Two's complement, so negative ids and raws have one encoding everywhere.
    void I32(int32_t v) noexcept {
        One([&](ByteCursor& c) { c.I32(v); });
    }
    void I64(int64_t v) noexcept {
        One([&](ByteCursor& c) { c.I64(v); });
    }
    void Bool(bool v) noexcept {
        One([&](ByteCursor& c) { c.Bool(v); });
    }
    void F(Fixed v) noexcept { I32(v.Raw()); }
    void W(Wide v) noexcept { I64(v.Raw()); }
    void V(const b2Vec2& v) noexcept {
        One([&](ByteCursor& c) { c.V(v); });
    }

    /// Raw bytes, already encoded (an image section).
    void Bytes(const void* data, size_t size) noexcept {
        Flush();
        Xxh3Update(&m_state, data, size);
    }

    /// The hash of everything written so far (the writer stays usable).
    uint64_t Digest() noexcept {
        Flush();
        return XXH3_64bits_digest(&m_state);
    }

private:
    template <class Fn>
    void One(Fn put) noexcept {
        ByteCursor c = Begin(8);
        put(c);
        End(c);
    }

    void Flush() noexcept {
        if (m_used != 0) Xxh3Update(&m_state, m_buffer, m_used);
        m_used = 0;
    }

    // 4 KiB amortise the update call over ~25 bodies, and the three writers the hash runs
    // at once stay in L1 together.
    static constexpr size_t kBuffer = 4096;
    static_assert(kMaxRecord <= kBuffer);
    XXH3_state_t m_state;
    uint8 m_buffer[kBuffer];
    size_t m_used = 0;
};

/// Opens a category's stream: version and category index, so that two categories with equal
/// bytes still hash differently.
inline void Tag(HashWriter& w, b2HashCategory c) noexcept {
    w.U32(b2_hashVersion);
    w.U32(static_cast<uint32>(c));
}

/// The world hash from the six category hashes (in b2HashCategory order).
inline uint64_t CombineCategories(const uint64_t categories[]) noexcept {
    HashWriter w;
    w.U32(b2_hashVersion);
    for (uint32 i = 0; i < static_cast<uint32>(b2HashCategory::e_count); ++i) w.U64(categories[i]);
    return w.Digest();
}

}  // namespace state_detail
}  // namespace lockbox
