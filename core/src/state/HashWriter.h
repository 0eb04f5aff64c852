#pragma once
// Internal to the state hash: a little-endian field writer in front of an XXH3-64 stream.
// Every value goes through an explicit width so the byte stream is the same on every
// platform (docs/determinism.md, "State hash").

// XXH3_state_t is only complete with the static-linking API (it lives on our stack).
#ifndef XXH_STATIC_LINKING_ONLY
#define XXH_STATIC_LINKING_ONLY
#endif
#include <xxhash.h>

#include <bit>
#include <cstddef>
#include <cstring>
#include <cstdint>

#include "lockbox/fixed/Math.h"

namespace lockbox {

namespace state_detail {

/// Streams little-endian fixed-width fields into XXH3-64. Not copyable (owns the state).
class HashWriter {
public:
    HashWriter() noexcept { XXH3_64bits_reset(&state_); }
    HashWriter(const HashWriter&) = delete;
    HashWriter& operator=(const HashWriter&) = delete;

    /// One unsigned field of `bytes` bytes (1, 2, 4 or 8), low byte first.
    void Put(uint64_t v, int bytes) noexcept {
        if (used_ + 8 > kBuffer) Flush();
        if constexpr (std::endian::native == std::endian::little) {
            // The host order is the stream order: copy the low `bytes` bytes at once.
            std::memcpy(buffer_ + used_, &v, 8);
            used_ += static_cast<size_t>(bytes);
        } else {
            for (int i = 0; i < bytes; ++i) buffer_[used_++] = static_cast<unsigned char>(v >> (8 * i));
        }
    }
    void U8(uint32_t v) noexcept { Put(v, 1); }
    void U16(uint32_t v) noexcept { Put(v, 2); }
    void U32(uint32_t v) noexcept { Put(v, 4); }
    void U64(uint64_t v) noexcept { Put(v, 8); }
    /// Two's complement, so negative ids and raws have one encoding everywhere.
    void I32(int32_t v) noexcept { Put(static_cast<uint32_t>(v), 4); }
    void I64(int64_t v) noexcept { Put(static_cast<uint64_t>(v), 8); }
    void Bool(bool v) noexcept { Put(v ? 1u : 0u, 1); }
    void F(Fixed v) noexcept { I32(v.Raw()); }
    void W(Wide v) noexcept { I64(v.Raw()); }
    void V(const b2Vec2& v) noexcept { F(v.x); F(v.y); }

    /// The hash of everything written so far (the writer stays usable).
    uint64_t Digest() noexcept {
        Flush();
        return XXH3_64bits_digest(&state_);
    }

private:
    void Flush() noexcept {
        if (used_ != 0) XXH3_64bits_update(&state_, buffer_, used_);
        used_ = 0;
    }

    // 2 KiB amortise the update call over ~15 bodies and let XXH3 take whole stripes.
    static constexpr size_t kBuffer = 2048;
    XXH3_state_t state_;
    unsigned char buffer_[kBuffer];
    size_t used_ = 0;
};

}  // namespace state_detail
}  // namespace lockbox
