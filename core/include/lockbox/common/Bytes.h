#pragma once
/// @file
/// Little-endian byte encoding for every format lockbox reads from outside: snapshot images,
/// replay files, lockstep and rollback datagrams, relay headers.
///
/// `bytes::Reader` is the one checked reader for untrusted bytes. It never reads past its
/// span, never asserts and never throws: a read that does not fit records the failure (why,
/// and the offset where the read started), returns zero, and every later read fails too, so a
/// parser reads a group of fields and checks `Ok()` once. `bytes::Writer` appends the same
/// encodings to a byte vector.
///
/// The encodings: unsigned and two's-complement integers of 1, 2, 4 and 8 bytes, low byte
/// first; minimal LEB128 varints (7 bits per byte, low group first, high bit set on every
/// byte but the last, at most 10 bytes); blobs (a u32 byte count, then the bytes).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

/// The little-endian byte codec shared by every format lockbox reads from outside.
namespace lockbox::bytes {

/// Why a Reader stopped reading (the first failure only).
enum class ReadError : uint8_t {
    e_none = 0,
    e_truncated,  ///< a read wanted more bytes than were left
    e_badVarint,  ///< a varint longer than 10 bytes, above 64 bits, or not spelled minimally
    e_refused,    ///< the parser refused a value it had read (Reader::Refuse)
};

/// Reads little-endian fields from a byte span, checking every read against the end.
class Reader {
public:
    /// Reads `bytes` from offset `start` (clamped to the span). Offsets are from the span's
    /// first byte.
    explicit Reader(std::span<const uint8_t> bytes, size_t start = 0) noexcept
        : m_data(bytes.data()), m_size(bytes.size()), m_at(start < bytes.size() ? start : bytes.size()) {}

    /// Fixed-width fields; 0 once the reader has failed.
    uint8_t U8() noexcept { return Get<uint8_t>(); }
    /// More fixed-width fields (2, 4 and 8 bytes, low byte first; the signed ones as two's
    /// complement); 0 once the reader has failed.
    ///@{
    uint16_t U16() noexcept { return Get<uint16_t>(); }
    uint32_t U32() noexcept { return Get<uint32_t>(); }
    uint64_t U64() noexcept { return Get<uint64_t>(); }
    int32_t I32() noexcept { return static_cast<int32_t>(Get<uint32_t>()); }
    int64_t I64() noexcept { return static_cast<int64_t>(Get<uint64_t>()); }
    ///@}

    /// A minimal LEB128 varint whose value fits 64 bits (e_badVarint otherwise).
    uint64_t Varint() noexcept {
        const size_t start = m_at;
        uint64_t v = 0;
        for (int i = 0; i < 10; ++i) {
            if (m_size - m_at < 1) return FailAt(start, ReadError::e_truncated);
            const uint8_t b = m_data[m_at++];
            // The tenth byte may hold bit 63 only.
            if (i == 9 && b > 1) return FailAt(start, ReadError::e_badVarint);
            v |= static_cast<uint64_t>(b & 0x7F) << (7 * i);
            if ((b & 0x80) == 0) {
                // A zero last byte after the first is a longer spelling of a shorter value.
                if (i > 0 && b == 0) return FailAt(start, ReadError::e_badVarint);
                return v;
            }
        }
        return FailAt(start, ReadError::e_badVarint);
    }

    /// The next `n` bytes as a view into the input (empty when fewer are left).
    std::span<const uint8_t> Bytes(size_t n) noexcept {
        if (m_size - m_at < n) [[unlikely]] {
            FailAt(m_at, ReadError::e_truncated);
            return {};
        }
        const std::span<const uint8_t> s(m_data + m_at, n);
        m_at += n;
        return s;
    }
    /// Copies the next `out.size()` bytes into `out`; false, and nothing copied, when fewer
    /// are left.
    bool Copy(std::span<uint8_t> out) noexcept {
        const std::span<const uint8_t> s = Bytes(out.size());
        if (s.size() != out.size()) return false;
        if (!s.empty()) std::memcpy(out.data(), s.data(), s.size());
        return true;
    }
    /// A blob: a u32 byte count, then that many bytes (viewed in place).
    std::span<const uint8_t> Blob() noexcept { return Bytes(U32()); }

    /// The next `n` bytes without moving past them (empty, and a failure, when fewer are
    /// left): a parser checks the room of a whole record once, then reads it from the view.
    std::span<const uint8_t> Peek(size_t n) noexcept {
        if (m_size - m_at < n) [[unlikely]] {
            FailAt(m_at, ReadError::e_truncated);
            return {};
        }
        return {m_data + m_at, n};
    }
    /// Moves past `n` bytes (e_truncated when fewer are left).
    void Skip(size_t n) noexcept { (void)Bytes(n); }

    /// Fails the reader at its current offset because the parser refused what it read (a
    /// value out of range, say); no effect once the reader has failed.
    void Refuse() noexcept { FailAt(m_at, ReadError::e_refused); }

    /// True until a read fails or the parser refuses a value.
    bool Ok() const noexcept { return m_error == ReadError::e_none; }
    /// The first failure (e_none while Ok()).
    ReadError Error() const noexcept { return m_error; }
    /// Where the failed read started, from the span's first byte (0 while Ok()).
    size_t ErrorOffset() const noexcept { return m_errorAt; }

    /// The offset of the next read, from the span's first byte.
    size_t Position() const noexcept { return m_at; }
    /// Bytes left to read (0 once the reader has failed).
    size_t Remaining() const noexcept { return m_size - m_at; }
    /// True when every byte has been read.
    bool AtEnd() const noexcept { return m_at == m_size; }

private:
    template <class T>
    T Get() noexcept {
        // One comparison: a failed reader has nothing left (FailAt), so this also refuses
        // every read after a failure.
        if (m_size - m_at < sizeof(T)) [[unlikely]]
            return static_cast<T>(FailAt(m_at, ReadError::e_truncated));
        T v = 0;
        if constexpr (std::endian::native == std::endian::little) {
            std::memcpy(&v, m_data + m_at, sizeof v);  // the stream order is the host order: one load
        } else {
            for (size_t i = 0; i < sizeof v; ++i) v = static_cast<T>(v | (static_cast<T>(m_data[m_at + i]) << (8 * i)));
        }
        m_at += sizeof v;
        return v;
    }

    /// Records the first failure, then leaves nothing to read. Returns 0 for the read.
    uint64_t FailAt(size_t at, ReadError error) noexcept {
        if (m_error == ReadError::e_none) {
            m_error = error;
            m_errorAt = at;
        }
        m_size = m_at;
        return 0;
    }

    const uint8_t* m_data;
    size_t m_size;
    size_t m_at;
    size_t m_errorAt = 0;
    ReadError m_error = ReadError::e_none;
};

/// Appends little-endian fields to a byte vector (after whatever it already holds).
class Writer {
public:
    /// A writer appending to `out`, which must outlive it.
    explicit Writer(std::vector<uint8_t>& out) noexcept : m_out(out) {}

    /// Unsigned fields of 1, 2, 4 and 8 bytes, low byte first.
    ///@{
    void U8(uint8_t v) { m_out.push_back(v); }
    void U16(uint16_t v) { Put(v); }
    void U32(uint32_t v) { Put(v); }
    void U64(uint64_t v) { Put(v); }
    ///@}
    /// Two's complement, so a negative value has one encoding everywhere.
    void I32(int32_t v) { Put(static_cast<uint32_t>(v)); }
    /// Two's complement, so a negative value has one encoding everywhere.
    void I64(int64_t v) { Put(static_cast<uint64_t>(v)); }

    /// The minimal LEB128 spelling of `v` (1 to 10 bytes).
    void Varint(uint64_t v) {
        while (v >= 0x80) {
            m_out.push_back(static_cast<uint8_t>(v | 0x80));
            v >>= 7;
        }
        m_out.push_back(static_cast<uint8_t>(v));
    }

    /// The bytes as they are, without a length (the reader must know the count).
    void Bytes(std::span<const uint8_t> b) { m_out.insert(m_out.end(), b.begin(), b.end()); }
    /// A blob: a u32 byte count, then the bytes (fewer than 2^32 of them).
    void Blob(std::span<const uint8_t> b) {
        U32(static_cast<uint32_t>(b.size()));
        Bytes(b);
    }

    /// Overwrites the 4 bytes at `at` (written earlier: a length known only after what it
    /// counts).
    void PatchU32(size_t at, uint32_t v) noexcept { Store(m_out.data() + at, v); }
    /// Overwrites the 8 bytes at `at` (a checksum of what follows it, say).
    void PatchU64(size_t at, uint64_t v) noexcept { Store(m_out.data() + at, v); }

    /// Bytes in the vector, which is where the next field goes.
    size_t Position() const noexcept { return m_out.size(); }

private:
    template <class T>
    void Put(T v) {
        for (size_t i = 0; i < sizeof v; ++i) m_out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    template <class T>
    static void Store(uint8_t* at, T v) noexcept {
        for (size_t i = 0; i < sizeof v; ++i) at[i] = static_cast<uint8_t>(v >> (8 * i));
    }

    std::vector<uint8_t>& m_out;
};

}  // namespace lockbox::bytes
