#pragma once
// Internal to the state code: unchecked little-endian field cursors over a span whose room
// the owner (HashWriter, FieldWriter, ImageReader) has checked once for a whole record. A
// cursor is a local value holding one pointer, so the compiler keeps it in a register for
// the record: a body's 27 fields cost 27 stores instead of 27 checks, loads and stores of a
// member write position (a store through uint8* may alias any member, so a member position
// is reloaded after every field). They exist beside lockbox's checked byte reader
// (lockbox/common/Bytes.h) for the records whose bounds are already known: the save writes
// the world's own state, and a restore's apply (SnapshotApply.cpp, JointState.h) reads again
// the records the parse has checked. Untrusted bytes are read through the checked reader
// only, or through a ReadCursor from ImageReader::Begin after its room check.

#include <bit>
#include <cstddef>
#include <cstring>

#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox::state_detail {

/// Writes fixed-width fields, low byte first, from a position with enough room (checked by
/// whoever made the cursor).
class ByteCursor {
public:
    explicit ByteCursor(uint8* at) noexcept : m_p(at) {}

    void U8(uint32 v) noexcept { Put(static_cast<uint8>(v)); }
    void U16(uint32 v) noexcept { Put(static_cast<uint16>(v)); }
    void U32(uint32 v) noexcept { Put(v); }
    void U64(uint64 v) noexcept { Put(v); }
    /// Two's complement, so negative ids and raws have one encoding everywhere.
    void I32(int32 v) noexcept { Put(static_cast<uint32>(v)); }
    void I64(int64_t v) noexcept { Put(static_cast<uint64>(v)); }
    void Bool(bool v) noexcept { Put(static_cast<uint8>(v ? 1 : 0)); }
    void F(Fixed v) noexcept { I32(v.Raw()); }
    void W(Wide v) noexcept { I64(v.Raw()); }
    void V(const b2Vec2& v) noexcept {
        F(v.x);
        F(v.y);
    }

    /// One past the last byte written.
    uint8* Position() const noexcept { return m_p; }

private:
    template <class T>
    void Put(T v) noexcept {
        if constexpr (std::endian::native == std::endian::little) {
            std::memcpy(m_p, &v, sizeof v);  // host order is stream order: one store
        } else {
            for (size_t i = 0; i < sizeof v; ++i) m_p[i] = static_cast<uint8>(static_cast<uint64>(v) >> (8 * i));
        }
        m_p += sizeof v;
    }

    uint8* m_p;
};

/// Reads fixed-width little-endian fields from a position with enough bytes left (checked by
/// whoever made the cursor).
class ReadCursor {
public:
    explicit ReadCursor(const uint8* at) noexcept : m_p(at) {}

    uint8 U8() noexcept { return Get<uint8>(); }
    uint16 U16() noexcept { return Get<uint16>(); }
    uint32 U32() noexcept { return Get<uint32>(); }
    uint64 U64() noexcept { return Get<uint64>(); }
    int32 I32() noexcept { return static_cast<int32>(Get<uint32>()); }
    int64_t I64() noexcept { return static_cast<int64_t>(Get<uint64>()); }
    Fixed F() noexcept { return Fixed::FromRaw(I32()); }
    Wide W() noexcept { return Wide::FromRaw(I64()); }
    b2Vec2 V() noexcept {
        const Fixed x = F();
        return b2Vec2(x, F());
    }

    /// Moves past `bytes` bytes without reading them.
    void Skip(size_t bytes) noexcept { m_p += bytes; }

    /// One past the last byte read.
    const uint8* Position() const noexcept { return m_p; }

private:
    template <class T>
    T Get() noexcept {
        T v = 0;
        if constexpr (std::endian::native == std::endian::little) {
            std::memcpy(&v, m_p, sizeof v);
        } else {
            for (size_t i = 0; i < sizeof v; ++i) v = static_cast<T>(v | (static_cast<T>(m_p[i]) << (8 * i)));
        }
        m_p += sizeof v;
        return v;
    }

    const uint8* m_p;
};

}  // namespace lockbox::state_detail
