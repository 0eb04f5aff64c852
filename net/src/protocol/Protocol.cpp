// The datagram header, names, and the repeat-bitmap input runs of the lockstep codec
// (Protocol.h). Message bodies are in ProtocolMessages.cpp.

#include "lockbox/net/Protocol.h"

#include <algorithm>
#include <cstring>

#include "protocol/WireIO.h"

namespace lockbox::net {

std::string_view RejectReasonName(RejectReason reason) noexcept {
    switch (reason) {
        case RejectReason::e_none: return "none";
        case RejectReason::e_protocolVersion: return "protocol version";
        case RejectReason::e_determinismVersion: return "determinism version";
        case RejectReason::e_full: return "full";
        case RejectReason::e_slotTaken: return "slot taken";
        case RejectReason::e_badToken: return "bad token";
        case RejectReason::e_hashMismatch: return "hash mismatch";
        case RejectReason::e_timeout: return "timeout";
        case RejectReason::e_left: return "left";
        case RejectReason::e_serverClosing: return "server closing";
        case RejectReason::e_count: break;
    }
    return "unknown";
}

std::string_view DecodeErrorName(DecodeError error) noexcept {
    switch (error) {
        case DecodeError::e_ok: return "ok";
        case DecodeError::e_tooShort: return "too short";
        case DecodeError::e_badMagic: return "bad magic";
        case DecodeError::e_badVersion: return "bad version";
        case DecodeError::e_badType: return "bad type";
        case DecodeError::e_truncated: return "truncated";
        case DecodeError::e_badVarint: return "bad varint";
        case DecodeError::e_badValue: return "bad value";
        case DecodeError::e_noShape: return "no shape";
        case DecodeError::e_incompatible: return "incompatible";
        case DecodeError::e_count: break;
    }
    return "unknown";
}

DecodeError DecodeHeader(std::span<const uint8_t> datagram, Header& header) noexcept {
    // A header alone says nothing: at least one message type byte must follow.
    if (datagram.size() < kHeaderBytes + 1) return DecodeError::e_tooShort;
    wire::Reader r(datagram);
    if (r.U16() != kProtocolMagic) return DecodeError::e_badMagic;
    header.version = r.U8();
    header.token = r.U32();
    header.sequence = r.U16();
    return header.version == kProtocolVersion ? DecodeError::e_ok : DecodeError::e_badVersion;
}

void DatagramWriter::Begin(const Header& header) {
    m_bytes.clear();
    m_messages = 0;
    bytes::Writer w(m_bytes);
    w.U16(kProtocolMagic);
    w.U8(header.version);
    w.U32(header.token);
    w.U16(header.sequence);
}

namespace wire {

void WriteRun(bytes::Writer& w, std::span<const uint8_t> bytes, size_t entries, size_t width, size_t stride) {
    std::vector<uint8_t> bitmap((entries + 7) / 8, 0);
    // The first frame's entries repeat an all-zero entry (idle input is the common case).
    auto same = [&](size_t i) {
        const uint8_t* e = bytes.data() + i * width;
        if (i >= stride) return width == 0 || std::memcmp(e, e - stride * width, width) == 0;
        for (size_t k = 0; k < width; ++k)
            if (e[k] != 0) return false;
        return true;
    };
    for (size_t i = 0; i < entries; ++i)
        if (same(i)) bitmap[i / 8] = static_cast<uint8_t>(bitmap[i / 8] | (1u << (i % 8)));
    w.Bytes(bitmap);
    for (size_t i = 0; i < entries; ++i)
        if (!same(i)) w.Bytes(bytes.subspan(i * width, width));
}

void ReadRun(Reader& r, std::vector<uint8_t>& out, size_t entries, size_t width, size_t stride) {
    std::vector<uint8_t> bitmap((entries + 7) / 8, 0);
    if (!r.Copy(bitmap)) return;
    // Padding bits past the last entry must be zero, or two spellings would decode alike.
    if (entries % 8 != 0 && (bitmap.back() >> (entries % 8)) != 0) {
        r.Fail(DecodeError::e_badValue);
        return;
    }
    out.assign(entries * width, 0);
    for (size_t i = 0; i < entries; ++i) {
        const bool repeat = ((bitmap[i / 8] >> (i % 8)) & 1u) != 0;
        uint8_t* entry = out.data() + i * width;
        if (repeat) {
            // Entries of the first frame repeat zeros, which `out` already holds.
            if (i >= stride && width > 0) std::memcpy(entry, entry - stride * width, width);
            continue;
        }
        if (!r.Copy({entry, width})) return;
        // An explicit entry equal to its repeat source must have been written as a repeat.
        bool same = true;
        if (i >= stride) {
            same = width == 0 || std::memcmp(entry, entry - stride * width, width) == 0;
        } else {
            for (size_t k = 0; k < width; ++k) same = same && entry[k] == 0;
        }
        if (same) {
            r.Fail(DecodeError::e_badValue);
            return;
        }
    }
}

}  // namespace wire
}  // namespace lockbox::net
