#pragma once
// Internal to the snapshot: std::streambuf adapters that let Cereal's portable binary
// archives write into a std::vector<uint8> (reusing its capacity) and read from a byte span
// without copying, plus the little-endian field writer/reader the state walk uses.

#include <cereal/archives/portable_binary.hpp>

#include <cstddef>
#include <istream>
#include <ostream>
#include <span>
#include <streambuf>
#include <vector>

#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

namespace lockbox::state_detail {

/// Appends to a vector: the put area is the vector's own storage, grown by doubling.
class VectorSinkBuf : public std::streambuf {
public:
    explicit VectorSinkBuf(std::vector<uint8>& out) : out_(out) {
        out_.resize(out_.capacity() < 4096 ? 4096 : out_.capacity());
        Reset(0);
    }
    /// Bytes written so far.
    size_t Position() const noexcept { return static_cast<size_t>(pptr() - pbase()); }
    /// Pointer to byte `offset` of the output (for patching lengths and checksums).
    uint8* At(size_t offset) noexcept { return out_.data() + offset; }
    /// Trims the vector to the bytes written.
    void Finish() { out_.resize(Position()); }

protected:
    int_type overflow(int_type ch) override {
        const size_t used = Position();
        out_.resize(out_.size() * 2);
        Reset(used);
        if (!traits_type::eq_int_type(ch, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(ch);
            pbump(1);
        }
        return traits_type::not_eof(ch);
    }

private:
    void Reset(size_t used) {
        char* base = reinterpret_cast<char*>(out_.data());
        setp(base, base + out_.size());
        // pbump takes an int: advance in int-sized steps.
        while (used > 0) {
            const int step = used > 0x40000000u ? 0x40000000 : static_cast<int>(used);
            pbump(step);
            used -= static_cast<size_t>(step);
        }
    }
    std::vector<uint8>& out_;
};

/// Reads a byte span in place.
class SpanSourceBuf : public std::streambuf {
public:
    explicit SpanSourceBuf(std::span<const uint8> bytes) {
        // The get area is never written through; std::streambuf just wants char*.
        char* base = const_cast<char*>(reinterpret_cast<const char*>(bytes.data()));
        setg(base, base, base + bytes.size());
    }
    /// Bytes consumed so far.
    size_t Position() const noexcept { return static_cast<size_t>(gptr() - eback()); }
    /// Bytes left.
    size_t Remaining() const noexcept { return static_cast<size_t>(egptr() - gptr()); }
};

/// The state walk's writer interface over a Cereal portable binary archive (little-endian).
class SnapshotWriter {
public:
    explicit SnapshotWriter(std::vector<uint8>& out)
        : buf_(out), stream_(&buf_), archive_(stream_, cereal::PortableBinaryOutputArchive::Options::LittleEndian()) {}

    void U8(uint32 v) { archive_(static_cast<uint8>(v)); }
    void U16(uint32 v) { archive_(static_cast<uint16>(v)); }
    void U32(uint32 v) { archive_(v); }
    void U64(uint64 v) { archive_(v); }
    void I32(int32 v) { archive_(v); }
    void I64(int64_t v) { archive_(v); }
    void Bool(bool v) { U8(v ? 1u : 0u); }
    void F(Fixed v) { I32(v.Raw()); }
    void W(Wide v) { I64(v.Raw()); }
    void V(const b2Vec2& v) { F(v.x); F(v.y); }

    size_t Position() const noexcept { return buf_.Position(); }
    /// Overwrites 4 (or 8) bytes at offset, little-endian, after they were written.
    void Patch32(size_t offset, uint32 v) noexcept {
        for (int i = 0; i < 4; ++i) *buf_.At(offset + static_cast<size_t>(i)) = static_cast<uint8>(v >> (8 * i));
    }
    void Patch64(size_t offset, uint64 v) noexcept {
        for (int i = 0; i < 8; ++i) *buf_.At(offset + static_cast<size_t>(i)) = static_cast<uint8>(v >> (8 * i));
    }
    const uint8* Data(size_t offset) noexcept { return buf_.At(offset); }
    void Finish() { buf_.Finish(); }

private:
    VectorSinkBuf buf_;
    std::ostream stream_;
    cereal::PortableBinaryOutputArchive archive_;
};

/// Raised by SnapshotReader when the image ends early (mapped to e_truncated).
struct TruncatedImage {};

/// The reading side: a Cereal portable binary archive over a span. Short reads throw
/// TruncatedImage (Cereal throws its own exception, translated here).
class SnapshotReader {
public:
    /// The span must start with Cereal's endianness flag (checked by the caller).
    explicit SnapshotReader(std::span<const uint8> bytes)
        : buf_(bytes), stream_(&buf_), archive_(Open(stream_)) {}

    uint8 U8() { return Get<uint8>(); }
    uint16 U16() { return Get<uint16>(); }
    uint32 U32() { return Get<uint32>(); }
    uint64 U64() { return Get<uint64>(); }
    int32 I32() { return Get<int32>(); }
    int64_t I64() { return Get<int64_t>(); }
    Fixed F() { return Fixed::FromRaw(I32()); }
    Wide W() { return Wide::FromRaw(I64()); }
    b2Vec2 V() {
        const Fixed x = F();
        return b2Vec2(x, F());
    }

    size_t Position() const noexcept { return buf_.Position(); }
    size_t Remaining() const noexcept { return buf_.Remaining(); }

private:
    static cereal::PortableBinaryInputArchive Open(std::istream& stream) {
        try {
            return cereal::PortableBinaryInputArchive(stream);
        } catch (const cereal::Exception&) {
            throw TruncatedImage{};
        }
    }
    template <class T>
    T Get() {
        T value{};
        try {
            archive_(value);
        } catch (const cereal::Exception&) {
            throw TruncatedImage{};
        }
        return value;
    }

    SpanSourceBuf buf_;
    std::istream stream_;
    cereal::PortableBinaryInputArchive archive_;
};

}  // namespace lockbox::state_detail
