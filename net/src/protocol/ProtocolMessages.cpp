// Message bodies of the lockstep codec (Protocol.h): one encoder and one decoder per message,
// each checking the same ranges, so whatever decodes encodes back to the same bytes.

#include <algorithm>
#include <type_traits>

#include "lockbox/net/Protocol.h"
#include "protocol/WireIO.h"

namespace lockbox::net {
namespace {

using bytes::Writer;
using wire::Reader;

constexpr uint64_t kMaxFrame = 0x7FFFFFFFull;

bool FrameOk(int32_t f) { return f >= 0; }
bool ShapeOk(const SessionShape& s) {
    return s.playerCount >= 1 && s.playerCount <= kMaxPlayers && s.inputBytes <= kMaxInputBytes;
}
// Frames of a run of `bytes` for `entriesPerFrame` entries of the shape's width, or 0 when the
// size does not divide evenly or the count is out of 1 .. kMaxRunFrames.
size_t RunFrames(size_t bytes, size_t perFrameBytes) {
    if (perFrameBytes == 0) return 0;  // zero-byte inputs cannot say how many frames they hold
    if (bytes == 0 || bytes % perFrameBytes != 0) return 0;
    const size_t n = bytes / perFrameBytes;
    return n <= kMaxRunFrames ? n : 0;
}

// ---- encoders: false when a field is out of range ----
bool Enc(Writer& w, const Hello& m, const SessionShape&) {
    if (m.requestedSlot != kAnySlot && m.requestedSlot >= kMaxPlayers) return false;
    w.U32(m.determinismVersion);
    w.U32(m.token);
    w.U8(m.requestedSlot);
    w.Varint(m.clientTime);
    return true;
}
bool Enc(Writer& w, const Welcome& m, const SessionShape&) {
    if (m.playerCount < 1 || m.playerCount > kMaxPlayers || m.slot >= m.playerCount) return false;
    if (m.inputBytes < 1 || m.inputBytes > kMaxInputBytes || m.tickRate < 1 || m.hashInterval < 1 ||
        !FrameOk(m.startFrame) || m.token == 0)
        return false;
    w.U8(m.slot);
    w.U8(m.playerCount);
    w.U16(m.inputBytes);
    w.U16(m.tickRate);
    w.U8(m.inputDelay);
    w.Varint(m.hashInterval);
    w.Varint(static_cast<uint64_t>(m.startFrame));
    w.U32(m.token);
    w.U8(m.lateJoin ? 1 : 0);
    w.Varint(m.echoTime);
    w.Varint(m.holdMicros);
    return true;
}
bool Enc(Writer& w, const Reject& m, const SessionShape&) {
    if (m.reason >= RejectReason::e_count) return false;
    w.U8(static_cast<uint8_t>(m.reason));
    return true;
}
bool Enc(Writer& w, const Inputs& m, const SessionShape& s) {
    if (!ShapeOk(s) || m.slot >= s.playerCount || !FrameOk(m.firstFrame)) return false;
    const size_t n = RunFrames(m.bytes.size(), s.inputBytes);
    if (n == 0 || static_cast<uint64_t>(m.firstFrame) + n - 1 > kMaxFrame) return false;
    w.U8(m.slot);
    w.Varint(static_cast<uint64_t>(m.firstFrame));
    w.U8(static_cast<uint8_t>(n));
    wire::WriteRun(w, m.bytes, n, s.inputBytes, 1);
    return true;
}
bool Enc(Writer& w, const InputAck& m, const SessionShape&) {
    if (!FrameOk(m.nextFrame) || !FrameOk(m.hashFrame)) return false;
    w.Varint(static_cast<uint64_t>(m.nextFrame));
    w.Varint(static_cast<uint64_t>(m.hashFrame));
    return true;
}
bool Enc(Writer& w, const Confirmed& m, const SessionShape& s) {
    if (!ShapeOk(s) || !FrameOk(m.firstFrame)) return false;
    const size_t n = RunFrames(m.bytes.size(), size_t{s.inputBytes} * s.playerCount);
    if (n == 0 || static_cast<uint64_t>(m.firstFrame) + n - 1 > kMaxFrame) return false;
    w.Varint(static_cast<uint64_t>(m.firstFrame));
    w.U8(static_cast<uint8_t>(n));
    wire::WriteRun(w, m.bytes, n * s.playerCount, s.inputBytes, s.playerCount);
    return true;
}
bool Enc(Writer& w, const ConfirmedAck& m, const SessionShape&) {
    if (!FrameOk(m.nextFrame)) return false;
    w.Varint(static_cast<uint64_t>(m.nextFrame));
    return true;
}
bool Enc(Writer& w, const Ping& m, const SessionShape&) {
    w.Varint(m.time);
    return true;
}
bool Enc(Writer& w, const Pong& m, const SessionShape&) {
    w.Varint(m.echoTime);
    w.Varint(m.holdMicros);
    return true;
}
bool Enc(Writer& w, const HashReport& m, const SessionShape&) {
    if (!FrameOk(m.frame)) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    w.U64(m.hash);
    return true;
}
bool Enc(Writer&, const KeepAlive&, const SessionShape&) { return true; }
bool Enc(Writer& w, const Disconnect& m, const SessionShape&) {
    if (m.reason >= RejectReason::e_count) return false;
    w.U8(static_cast<uint8_t>(m.reason));
    return true;
}
bool Enc(Writer& w, const SnapshotRequest& m, const SessionShape&) {
    if (!FrameOk(m.minFrame)) return false;
    w.Varint(static_cast<uint64_t>(m.minFrame));
    return true;
}
// Bytes chunk `index` of a `total`-byte snapshot must carry, or 0 when the index is past the end.
uint64_t SnapshotChunkLength(uint64_t total, uint64_t index) {
    const uint64_t offset = index * kSnapshotChunkBytes;  // index < 2^32: no overflow
    if (offset >= total) return 0;
    return std::min<uint64_t>(kSnapshotChunkBytes, total - offset);
}
bool Enc(Writer& w, const SnapshotChunk& m, const SessionShape&) {
    if (!FrameOk(m.frame) || m.totalSize < 1 || m.totalSize > kMaxSnapshotBytes) return false;
    const uint64_t len = SnapshotChunkLength(m.totalSize, m.index);
    if (len == 0 || m.bytes.size() != len) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    w.Varint(m.totalSize);
    w.Varint(m.index);
    w.Bytes(m.bytes);
    return true;
}
bool Enc(Writer& w, const SnapshotAck& m, const SessionShape&) {
    if (!FrameOk(m.frame)) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    w.Varint(m.index);
    return true;
}
bool Enc(Writer& w, const Admit& m, const SessionShape&) {
    if (!FrameOk(m.joinFrame)) return false;
    w.Varint(static_cast<uint64_t>(m.joinFrame));
    return true;
}
bool Enc(Writer& w, const DesyncNotice& m, const SessionShape&) {
    if (!FrameOk(m.frame)) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    return true;
}

// ---- decoders: errors stick in the reader ----
void Dec(Reader& r, Hello& m, const SessionShape&) {
    m.determinismVersion = r.U32();
    m.token = r.U32();
    m.requestedSlot = r.U8();
    m.clientTime = r.Varint();
    if (m.requestedSlot != kAnySlot && m.requestedSlot >= kMaxPlayers) r.Fail(DecodeError::e_badValue);
}
void Dec(Reader& r, Welcome& m, const SessionShape&) {
    m.slot = r.U8();
    m.playerCount = r.U8();
    m.inputBytes = r.U16();
    m.tickRate = r.U16();
    m.inputDelay = r.U8();
    const uint64_t interval = r.Varint();
    m.startFrame = r.Frame();
    m.token = r.U32();
    const uint8_t flags = r.U8();
    m.echoTime = r.Varint();
    m.holdMicros = r.Varint();
    if (!r.Ok()) return;
    if (m.playerCount < 1 || m.playerCount > kMaxPlayers || m.slot >= m.playerCount || m.inputBytes < 1 ||
        m.inputBytes > kMaxInputBytes || m.tickRate < 1 || interval < 1 || interval > 0xFFFFFFFFull || m.token == 0 ||
        flags > 1) {
        r.Fail(DecodeError::e_badValue);
        return;
    }
    m.hashInterval = static_cast<uint32_t>(interval);
    m.lateJoin = flags == 1;
}
void Dec(Reader& r, Reject& m, const SessionShape&) {
    const uint8_t v = r.U8();
    if (v >= static_cast<uint8_t>(RejectReason::e_count)) r.Fail(DecodeError::e_badValue);
    m.reason = static_cast<RejectReason>(v);
}
void Dec(Reader& r, Inputs& m, const SessionShape& s) {
    if (!ShapeOk(s) || s.inputBytes == 0) return r.Fail(DecodeError::e_noShape);
    m.slot = r.U8();
    m.firstFrame = r.Frame();
    const uint8_t n = r.U8();
    if (!r.Ok()) return;
    if (m.slot >= s.playerCount || n == 0 || static_cast<uint64_t>(m.firstFrame) + n - 1 > kMaxFrame)
        return r.Fail(DecodeError::e_badValue);
    wire::ReadRun(r, m.bytes, n, s.inputBytes, 1);
}
void Dec(Reader& r, InputAck& m, const SessionShape&) {
    m.nextFrame = r.Frame();
    m.hashFrame = r.Frame();
}
void Dec(Reader& r, Confirmed& m, const SessionShape& s) {
    if (!ShapeOk(s) || s.inputBytes == 0) return r.Fail(DecodeError::e_noShape);
    m.firstFrame = r.Frame();
    const uint8_t n = r.U8();
    if (!r.Ok()) return;
    if (n == 0 || static_cast<uint64_t>(m.firstFrame) + n - 1 > kMaxFrame) return r.Fail(DecodeError::e_badValue);
    wire::ReadRun(r, m.bytes, size_t{n} * s.playerCount, s.inputBytes, s.playerCount);
}
void Dec(Reader& r, ConfirmedAck& m, const SessionShape&) { m.nextFrame = r.Frame(); }
void Dec(Reader& r, Ping& m, const SessionShape&) { m.time = r.Varint(); }
void Dec(Reader& r, Pong& m, const SessionShape&) {
    m.echoTime = r.Varint();
    m.holdMicros = r.Varint();
}
void Dec(Reader& r, HashReport& m, const SessionShape&) {
    m.frame = r.Frame();
    m.hash = r.U64();
}
void Dec(Reader&, KeepAlive&, const SessionShape&) {}
void Dec(Reader& r, Disconnect& m, const SessionShape&) {
    const uint8_t v = r.U8();
    if (v >= static_cast<uint8_t>(RejectReason::e_count)) r.Fail(DecodeError::e_badValue);
    m.reason = static_cast<RejectReason>(v);
}
void Dec(Reader& r, SnapshotRequest& m, const SessionShape&) { m.minFrame = r.Frame(); }
void Dec(Reader& r, SnapshotChunk& m, const SessionShape&) {
    m.frame = r.Frame();
    const uint64_t total = r.Varint();
    const uint64_t index = r.Varint();
    if (!r.Ok()) return;
    if (total < 1 || total > kMaxSnapshotBytes || index > 0xFFFFFFFFull) return r.Fail(DecodeError::e_badValue);
    const uint64_t len = SnapshotChunkLength(total, index);
    if (len == 0) return r.Fail(DecodeError::e_badValue);
    m.totalSize = static_cast<uint32_t>(total);
    m.index = static_cast<uint32_t>(index);
    m.bytes.resize(len);
    r.Copy(m.bytes);
}
void Dec(Reader& r, SnapshotAck& m, const SessionShape&) {
    m.frame = r.Frame();
    const uint64_t index = r.Varint();
    if (index > 0xFFFFFFFFull) r.Fail(DecodeError::e_badValue);
    m.index = static_cast<uint32_t>(index);
}
void Dec(Reader& r, Admit& m, const SessionShape&) { m.joinFrame = r.Frame(); }
void Dec(Reader& r, DesyncNotice& m, const SessionShape&) { m.frame = r.Frame(); }

// Decodes the message of variant index I when it matches `type`.
template <size_t I>
bool DecodeIndex(size_t type, Reader& r, const SessionShape& s, std::vector<Message>& out) {
    if constexpr (I < std::variant_size_v<Message>) {
        if (type != I) return DecodeIndex<I + 1>(type, r, s, out);
        std::variant_alternative_t<I, Message> m{};
        Dec(r, m, s);
        if (r.Ok()) out.emplace_back(std::move(m));
        return true;
    } else {
        return false;
    }
}

bool EncodeAny(Writer& w, const Message& message, const SessionShape& shape) {
    w.U8(static_cast<uint8_t>(message.index() + 1));
    return std::visit([&](const auto& m) { return Enc(w, m, shape); }, message);
}

}  // namespace

DecodeError DecodeDatagram(std::span<const uint8_t> datagram, const SessionShape& shape, Header& header,
                           std::vector<Message>& out) {
    out.clear();
    const DecodeError h = DecodeHeader(datagram, header);
    if (h != DecodeError::e_ok) return h;
    Reader r(datagram.subspan(kHeaderBytes));
    while (!r.AtEnd()) {
        const uint8_t type = r.U8();
        if (type == 0 || !DecodeIndex<0>(size_t{type} - 1, r, shape, out)) {
            out.clear();
            return DecodeError::e_badType;
        }
        if (!r.Ok()) {
            out.clear();
            return r.Failure();
        }
    }
    return DecodeError::e_ok;
}

bool DatagramWriter::Add(const Message& message, const SessionShape& shape, size_t limit) {
    m_scratch.clear();
    Writer w(m_scratch);
    if (!EncodeAny(w, message, shape)) return false;
    if (m_bytes.size() + m_scratch.size() > limit) return false;
    m_bytes.insert(m_bytes.end(), m_scratch.begin(), m_scratch.end());
    ++m_messages;
    return true;
}

size_t DatagramWriter::SizeOf(const Message& message, const SessionShape& shape) {
    std::vector<uint8_t> tmp;
    Writer w(tmp);
    return EncodeAny(w, message, shape) ? tmp.size() : 0;
}

}  // namespace lockbox::net
