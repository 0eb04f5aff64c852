#pragma once
// Byte-level reading and writing for the lockstep codec (Protocol.cpp, ProtocolMessages.cpp):
// little-endian fixed widths, minimal LEB128 varints, and the repeat-bitmap input runs. The
// reader never reads past its span; the first failure sticks so callers check once at the end.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "lockbox/net/Protocol.h"

namespace lockbox::net::wire {

/// Appends little-endian fields to a byte vector.
class Writer {
public:
    explicit Writer(std::vector<uint8_t>& out) : m_out(out) {}
    void U8(uint8_t v) { m_out.push_back(v); }
    void U16(uint16_t v) {
        U8(static_cast<uint8_t>(v));
        U8(static_cast<uint8_t>(v >> 8));
    }
    void U32(uint32_t v) {
        for (int i = 0; i < 4; ++i) U8(static_cast<uint8_t>(v >> (8 * i)));
    }
    void U64(uint64_t v) {
        for (int i = 0; i < 8; ++i) U8(static_cast<uint8_t>(v >> (8 * i)));
    }
    /// Minimal LEB128: 7 bits per byte, low group first, high bit set on all but the last.
    void Var(uint64_t v) {
        while (v >= 0x80) {
            U8(static_cast<uint8_t>(v | 0x80));
            v >>= 7;
        }
        U8(static_cast<uint8_t>(v));
    }
    void Bytes(std::span<const uint8_t> b) { m_out.insert(m_out.end(), b.begin(), b.end()); }

private:
    std::vector<uint8_t>& m_out;
};

/// Reads fields from a span; after the first error every read returns 0 and error() says why.
class Reader {
public:
    explicit Reader(std::span<const uint8_t> in) : m_in(in) {}
    bool ok() const noexcept { return m_error == DecodeError::e_ok; }
    DecodeError error() const noexcept { return m_error; }
    void Fail(DecodeError e) noexcept {
        if (ok()) m_error = e;
    }
    size_t Remaining() const noexcept { return m_in.size() - m_at; }
    bool AtEnd() const noexcept { return m_at == m_in.size(); }

    uint8_t U8() noexcept {
        if (!Need(1)) return 0;
        return m_in[m_at++];
    }
    uint16_t U16() noexcept {
        if (!Need(2)) return 0;
        const uint16_t v = static_cast<uint16_t>(m_in[m_at] | (m_in[m_at + 1] << 8));
        m_at += 2;
        return v;
    }
    uint32_t U32() noexcept {
        if (!Need(4)) return 0;
        uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(m_in[m_at + static_cast<size_t>(i)]) << (8 * i);
        m_at += 4;
        return v;
    }
    uint64_t U64() noexcept {
        if (!Need(8)) return 0;
        uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(m_in[m_at + static_cast<size_t>(i)]) << (8 * i);
        m_at += 8;
        return v;
    }
    /// A minimal LEB128 of at most 10 bytes whose value fits 64 bits.
    uint64_t Var() noexcept {
        uint64_t v = 0;
        for (int i = 0; i < 10; ++i) {
            if (!Need(1)) return 0;
            const uint8_t b = m_in[m_at++];
            // The tenth byte holds bit 63 only.
            if (i == 9 && b > 1) {
                Fail(DecodeError::e_badVarint);
                return 0;
            }
            v |= static_cast<uint64_t>(b & 0x7F) << (7 * i);
            if ((b & 0x80) == 0) {
                // A zero last byte after the first would be a longer spelling of a shorter value.
                if (i > 0 && b == 0) {
                    Fail(DecodeError::e_badVarint);
                    return 0;
                }
                return v;
            }
        }
        Fail(DecodeError::e_badVarint);
        return 0;
    }
    /// A varint that must be a frame number (0 .. INT32_MAX).
    int32_t Frame() noexcept {
        const uint64_t v = Var();
        if (v > 0x7FFFFFFFull) {
            Fail(DecodeError::e_badValue);
            return 0;
        }
        return static_cast<int32_t>(v);
    }
    /// Copies n bytes out (nothing on failure).
    bool Bytes(uint8_t* out, size_t n) noexcept {
        if (!Need(n)) return false;
        if (n > 0) std::memcpy(out, m_in.data() + m_at, n);
        m_at += n;
        return true;
    }

private:
    bool Need(size_t n) noexcept {
        if (!ok()) return false;
        if (Remaining() < n) {
            Fail(DecodeError::e_truncated);
            return false;
        }
        return true;
    }
    std::span<const uint8_t> m_in;
    size_t m_at = 0;
    DecodeError m_error = DecodeError::e_ok;
};

/// Writes `entries` entries of `width` bytes with the repeat bitmap: bit i (LSB first) set
/// when entry i equals its repeat source, entry i - stride (the same player one frame
/// earlier), or all zeros for i < stride; only the entries not marked follow the bitmap.
void WriteRun(Writer& w, std::span<const uint8_t> bytes, size_t entries, size_t width, size_t stride);
/// Reads what WriteRun wrote into `out` (resized to entries * width). Refuses a non-zero
/// padding bit and an explicit entry equal to its repeat source (so the encoding stays
/// canonical).
void ReadRun(Reader& r, std::vector<uint8_t>& out, size_t entries, size_t width, size_t stride);

}  // namespace lockbox::net::wire
