#pragma once
// Internal to the snapshot: the byte encodings of the save. The fixed header goes through
// Cereal's portable binary archive (HeaderSink/HeaderSource adapt it to memory); the sections
// are written by FieldWriter, which the state walk drives through unchecked ByteCursors (the
// world's own state needs no checks, only room). Per-field Cereal calls cost ~20 ns each
// through std::streambuf and made save plus restore several times the step budget; these
// cost ~1 ns. Images are read back through ImageReader (SnapshotCheck.h), on lockbox's checked
// byte reader (lockbox/common/Bytes.h), which writes the same encoding.

#include <bit>
#include <cstddef>
#include <cstring>
#include <span>
#include <streambuf>
#include <vector>

#include "ByteCursor.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox::state_detail {

/// A std::streambuf writing into a fixed byte array (the header).
class HeaderSink : public std::streambuf {
public:
    HeaderSink(uint8* bytes, size_t size) {
        char* base = reinterpret_cast<char*>(bytes);
        setp(base, base + size);
    }
    size_t Written() const noexcept { return static_cast<size_t>(pptr() - pbase()); }
};

/// A std::streambuf reading a byte span in place (the header).
class HeaderSource : public std::streambuf {
public:
    explicit HeaderSource(std::span<const uint8> bytes) {
        // The get area is never written through; std::streambuf just wants char*.
        char* base = const_cast<char*>(reinterpret_cast<const char*>(bytes.data()));
        setg(base, base, base + bytes.size());
    }
    size_t Consumed() const noexcept { return static_cast<size_t>(gptr() - eback()); }
};

/// Appends little-endian fixed-width fields to a vector from a start offset, growing it in
/// steps (a reused vector keeps its capacity: saving into it does not allocate). Hot
/// records go through Begin/End: one room check per record, then an unchecked cursor.
class FieldWriter {
public:
    FieldWriter(std::vector<uint8>& out, size_t start) : m_out(out), m_used(start) {
        if (m_out.size() < start) m_out.resize(start);
    }

    /// A cursor with room for `maxBytes` (any size); hand it back to End.
    ByteCursor Begin(size_t maxBytes) {
        if (maxBytes > m_out.size() - m_used) [[unlikely]]
            Grow(maxBytes);
        return ByteCursor(m_out.data() + m_used);
    }
    /// Takes the bytes a cursor from Begin wrote.
    void End(const ByteCursor& c) noexcept { m_used = static_cast<size_t>(c.Position() - m_out.data()); }

    void U8(uint32 v) {
        One([&](ByteCursor& c) { c.U8(v); });
    }
    void U16(uint32 v) {
        One([&](ByteCursor& c) { c.U16(v); });
    }
    void U32(uint32 v) {
        One([&](ByteCursor& c) { c.U32(v); });
    }
    void U64(uint64 v) {
        One([&](ByteCursor& c) { c.U64(v); });
    }
    void I32(int32 v) {
        One([&](ByteCursor& c) { c.I32(v); });
    }
    void I64(int64_t v) {
        One([&](ByteCursor& c) { c.I64(v); });
    }
    void Bool(bool v) {
        One([&](ByteCursor& c) { c.Bool(v); });
    }
    void F(Fixed v) { I32(v.Raw()); }
    void W(Wide v) { I64(v.Raw()); }
    void V(const b2Vec2& v) {
        One([&](ByteCursor& c) { c.V(v); });
    }

    size_t Position() const noexcept { return m_used; }
    /// Overwrites a 4-byte field written earlier (section lengths).
    void Patch32(size_t at, uint32 v) noexcept {
        for (int i = 0; i < 4; ++i) m_out[at + static_cast<size_t>(i)] = static_cast<uint8>(v >> (8 * i));
    }
    /// Trims the vector to the bytes written.
    void Finish() { m_out.resize(m_used); }

private:
    template <class Fn>
    void One(Fn put) {
        ByteCursor c = Begin(8);
        put(c);
        End(c);
    }

    /// Extends the vector by a step ahead of the writes. resize zero-fills what it adds, so
    /// the step is small: the fill lands in cache just before the fields overwrite it, where
    /// one resize to the whole capacity cost a cold fill of up to the whole image per save.
    /// A reused vector keeps its capacity, so this does not reallocate.
    [[gnu::noinline]] void Grow(size_t maxBytes) {
        constexpr size_t kStep = 16 * 1024;
        m_out.resize(m_used + (maxBytes > kStep ? maxBytes : kStep));
    }

    std::vector<uint8>& m_out;
    size_t m_used;
};

}  // namespace lockbox::state_detail
