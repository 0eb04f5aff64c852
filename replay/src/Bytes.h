#pragma once
// Little-endian fixed-width encoding for replay payloads (private to the replay module).

#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "lockbox/common/Settings.h"

namespace lockbox::replay::detail {

/// Appends little-endian integers to a byte vector.
class ByteWriter {
public:
    explicit ByteWriter(std::vector<uint8>& out) : m_out(out) {}
    void U8(uint8 v) { m_out.push_back(v); }
    void U16(uint16 v) { Le(v, 2); }
    void U32(uint32 v) { Le(v, 4); }
    void U64(uint64 v) { Le(v, 8); }
    void I32(int32 v) { U32(static_cast<uint32>(v)); }
    void Bytes(std::span<const uint8> b) { m_out.insert(m_out.end(), b.begin(), b.end()); }
    /// A u32 length then the bytes.
    void Blob(std::span<const uint8> b) {
        U32(static_cast<uint32>(b.size()));
        Bytes(b);
    }

private:
    void Le(uint64 v, int n) {
        for (int i = 0; i < n; ++i) m_out.push_back(static_cast<uint8>(v >> (8 * i)));
    }
    std::vector<uint8>& m_out;
};

/// Reads little-endian integers; any read past the end sets failed() and returns zeros, so a
/// parser checks once after a group of reads.
class ByteReader {
public:
    explicit ByteReader(std::span<const uint8> in) : m_in(in) {}
    uint8 U8() { return static_cast<uint8>(Le(1)); }
    uint16 U16() { return static_cast<uint16>(Le(2)); }
    uint32 U32() { return static_cast<uint32>(Le(4)); }
    uint64 U64() { return Le(8); }
    int32 I32() { return static_cast<int32>(U32()); }
    /// n bytes as a view into the input (empty and failed when fewer remain).
    std::span<const uint8> Bytes(size_t n) {
        if (m_failed || n > Remaining()) {
            m_failed = true;
            return {};
        }
        std::span<const uint8> s = m_in.subspan(m_pos, n);
        m_pos += n;
        return s;
    }
    /// A u32 length then that many bytes.
    std::span<const uint8> Blob() { return Bytes(U32()); }
    size_t Remaining() const noexcept { return m_in.size() - m_pos; }
    size_t Position() const noexcept { return m_pos; }
    bool failed() const noexcept { return m_failed; }

private:
    uint64 Le(int n) {
        if (m_failed || static_cast<size_t>(n) > Remaining()) {
            m_failed = true;
            return 0;
        }
        uint64 v = 0;
        for (int i = 0; i < n; ++i) v |= static_cast<uint64>(m_in[m_pos + static_cast<size_t>(i)]) << (8 * i);
        m_pos += static_cast<size_t>(n);
        return v;
    }
    std::span<const uint8> m_in;
    size_t m_pos = 0;
    bool m_failed = false;
};

}  // namespace lockbox::replay::detail
