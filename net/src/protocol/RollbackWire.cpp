// The rollback message codec (RollbackProtocol.h) on the lockstep codec's primitives
// (WireIO.h): fixed little-endian widths, minimal varints, repeat-bitmap input runs.

#include <algorithm>
#include <climits>
#include <type_traits>

#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/RollbackSession.h"
#include "protocol/WireIO.h"

namespace lockbox::net {

namespace {

using bytes::Writer;
using wire::Reader;

bool ShapeOk(const RollbackShape& s) noexcept {
    return s.players >= 1 && s.players <= kRollbackMaxPlayers && s.inputBytes >= 1 &&
           s.inputBytes <= kRollbackMaxInputBytes;
}

// Zigzag: small magnitudes of either sign become small varints; computed in uint32 so no
// signed shift or overflow happens.
uint64_t Zig(int32_t v) noexcept {
    const uint32_t u = static_cast<uint32_t>(v);
    return static_cast<uint64_t>((u << 1) ^ (v < 0 ? 0xFFFFFFFFu : 0u));
}
int32_t Unzig(uint64_t z) noexcept {
    const uint32_t u = static_cast<uint32_t>(z);
    const uint32_t v = (u >> 1) ^ (0u - (u & 1u));
    // Two's complement reinterpretation without a signed overflow.
    return v <= 0x7FFFFFFFu ? static_cast<int32_t>(v) : -static_cast<int32_t>(~v) - 1;
}

// Frame counts of a run: bytes must hold 1 .. kRollbackMaxRun whole rows.
size_t RunCount(size_t bytes, size_t row) noexcept {
    if (row == 0 || bytes == 0 || bytes % row != 0) return 0;
    const size_t n = bytes / row;
    return n <= kRollbackMaxRun ? n : 0;
}

bool Enc(Writer& w, const RbInputs& m, const RollbackShape& s) {
    if (m.player >= s.players || m.firstFrame < 0) return false;
    const size_t n = RunCount(m.bytes.size(), s.inputBytes);
    if (n == 0) return false;
    w.U8(m.player);
    w.Varint(static_cast<uint64_t>(m.firstFrame));
    w.Varint(n);
    wire::WriteRun(w, m.bytes, n, s.inputBytes, 1);
    return true;
}
void Dec(Reader& r, RbInputs& m, const RollbackShape& s) {
    m.player = r.U8();
    if (r.Ok() && m.player >= s.players) r.Fail(DecodeError::e_badValue);
    m.firstFrame = r.Frame();
    const uint64_t n = r.Varint();
    if (r.Ok() && (n < 1 || n > kRollbackMaxRun)) r.Fail(DecodeError::e_badValue);
    if (r.Ok()) wire::ReadRun(r, m.bytes, static_cast<size_t>(n), s.inputBytes, 1);
}

bool Enc(Writer& w, const RbInputAck& m, const RollbackShape& s) {
    if (m.player >= s.players || m.nextFrame < 0) return false;
    w.U8(m.player);
    w.Varint(static_cast<uint64_t>(m.nextFrame));
    return true;
}
void Dec(Reader& r, RbInputAck& m, const RollbackShape& s) {
    m.player = r.U8();
    if (r.Ok() && m.player >= s.players) r.Fail(DecodeError::e_badValue);
    m.nextFrame = r.Frame();
}

bool Enc(Writer& w, const RbQuality& m, const RollbackShape&) {
    if (m.frame < 0) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    w.Varint(Zig(m.advantageMilli));
    w.Varint(m.time);
    w.U8(m.sequence);
    return true;
}
void Dec(Reader& r, RbQuality& m, const RollbackShape&) {
    m.frame = r.Frame();
    const uint64_t z = r.Varint();
    if (r.Ok() && z > 0xFFFFFFFFull) r.Fail(DecodeError::e_badValue);
    m.advantageMilli = Unzig(z);
    m.time = r.Varint();
    m.sequence = r.U8();
}

bool Enc(Writer& w, const RbQualityReply& m, const RollbackShape&) {
    w.Varint(m.echoTime);
    w.Varint(m.holdMicros);
    return true;
}
void Dec(Reader& r, RbQualityReply& m, const RollbackShape&) {
    m.echoTime = r.Varint();
    m.holdMicros = r.Varint();
}

bool Enc(Writer& w, const RbHash& m, const RollbackShape&) {
    if (m.frame < 0) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    w.U64(m.hash);
    return true;
}
void Dec(Reader& r, RbHash& m, const RollbackShape&) {
    m.frame = r.Frame();
    m.hash = r.U64();
}

bool Enc(Writer& w, const RbConfirmed& m, const RollbackShape& s) {
    if (m.firstFrame < 0) return false;
    const size_t n = RunCount(m.bytes.size(), static_cast<size_t>(s.players) * s.inputBytes);
    if (n == 0) return false;
    w.Varint(static_cast<uint64_t>(m.firstFrame));
    w.Varint(n);
    wire::WriteRun(w, m.bytes, n * s.players, s.inputBytes, s.players);
    return true;
}
void Dec(Reader& r, RbConfirmed& m, const RollbackShape& s) {
    m.firstFrame = r.Frame();
    const uint64_t n = r.Varint();
    if (r.Ok() && (n < 1 || n > kRollbackMaxRun)) r.Fail(DecodeError::e_badValue);
    if (r.Ok()) wire::ReadRun(r, m.bytes, static_cast<size_t>(n) * s.players, s.inputBytes, s.players);
}

bool Enc(Writer& w, const RbConfirmedAck& m, const RollbackShape&) {
    if (m.nextFrame < 0) return false;
    w.Varint(static_cast<uint64_t>(m.nextFrame));
    return true;
}
void Dec(Reader& r, RbConfirmedAck& m, const RollbackShape&) { m.nextFrame = r.Frame(); }

bool Enc(Writer&, const RbKeepAlive&, const RollbackShape&) { return true; }
void Dec(Reader&, RbKeepAlive&, const RollbackShape&) {}
bool Enc(Writer&, const RbDisconnect&, const RollbackShape&) { return true; }
void Dec(Reader&, RbDisconnect&, const RollbackShape&) {}

bool Enc(Writer& w, const RbJoinRequest& m, const RollbackShape&) {
    if (m.attempt < 1) return false;
    w.Varint(m.attempt);
    return true;
}
void Dec(Reader& r, RbJoinRequest& m, const RollbackShape&) {
    const uint64_t a = r.Varint();
    if (r.Ok() && (a < 1 || a > 0xFFFFFFFFull)) r.Fail(DecodeError::e_badValue);
    m.attempt = static_cast<uint32_t>(a);
}

// Payload bytes of chunk `index` of a `total`-byte snapshot; 0 when the index is past the end.
size_t RbSnapshotChunkLength(uint32_t total, uint32_t index) noexcept {
    const uint64_t offset = uint64_t{index} * kRbSnapshotChunkBytes;
    if (offset >= total) return 0;
    return static_cast<size_t>(std::min<uint64_t>(kRbSnapshotChunkBytes, total - offset));
}

bool Enc(Writer& w, const RbSnapshotChunk& m, const RollbackShape&) {
    if (m.frame < 0 || m.totalSize < 1 || m.totalSize > kRbMaxSnapshotBytes) return false;
    const size_t len = RbSnapshotChunkLength(m.totalSize, m.index);
    if (len == 0 || m.bytes.size() != len) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    w.Varint(m.totalSize);
    w.U64(m.checksum);
    w.Varint(m.index);
    w.Bytes(m.bytes);
    return true;
}
void Dec(Reader& r, RbSnapshotChunk& m, const RollbackShape&) {
    m.frame = r.Frame();
    const uint64_t total = r.Varint();
    if (r.Ok() && (total < 1 || total > kRbMaxSnapshotBytes)) r.Fail(DecodeError::e_badValue);
    m.totalSize = static_cast<uint32_t>(total);
    m.checksum = r.U64();
    const uint64_t index = r.Varint();
    // total <= 16 MiB, so an index past it is refused before any multiplication can wrap.
    if (r.Ok() && index >= (uint64_t{m.totalSize} + kRbSnapshotChunkBytes - 1) / kRbSnapshotChunkBytes)
        r.Fail(DecodeError::e_badValue);
    if (!r.Ok()) return;
    m.index = static_cast<uint32_t>(index);
    m.bytes.resize(RbSnapshotChunkLength(m.totalSize, m.index));
    r.Copy(m.bytes);
}

bool Enc(Writer& w, const RbSnapshotAck& m, const RollbackShape&) {
    if (m.frame < 0 || m.index >= kRbMaxSnapshotBytes / kRbSnapshotChunkBytes) return false;
    w.Varint(static_cast<uint64_t>(m.frame));
    w.Varint(m.index);
    return true;
}
void Dec(Reader& r, RbSnapshotAck& m, const RollbackShape&) {
    m.frame = r.Frame();
    const uint64_t index = r.Varint();
    if (r.Ok() && index >= kRbMaxSnapshotBytes / kRbSnapshotChunkBytes) r.Fail(DecodeError::e_badValue);
    m.index = static_cast<uint32_t>(index);
}

bool Enc(Writer& w, const RbView& m, const RollbackShape& s) {
    if (m.received.size() != s.players) return false;
    int32_t base = INT32_MAX;
    for (int32_t v : m.received) {
        if (v < 0) return false;
        base = std::min(base, v);
    }
    w.Varint(static_cast<uint64_t>(base));
    for (int32_t v : m.received) w.Varint(static_cast<uint64_t>(v - base));
    return true;
}
void Dec(Reader& r, RbView& m, const RollbackShape& s) {
    const int32_t base = r.Frame();
    m.received.assign(s.players, 0);
    bool zero = false;
    for (uint32_t i = 0; i < s.players && r.Ok(); ++i) {
        const uint64_t d = r.Varint();
        // base + d must stay a frame number; checked before adding, so nothing overflows.
        if (r.Ok() && d > static_cast<uint64_t>(INT32_MAX - base)) r.Fail(DecodeError::e_badValue);
        if (!r.Ok()) return;
        zero = zero || d == 0;
        m.received[i] = base + static_cast<int32_t>(d);
    }
    // The base must be the smallest entry: any other base would be a second encoding.
    if (r.Ok() && !zero) r.Fail(DecodeError::e_badValue);
}

bool Enc(Writer& w, const RbFrozen& m, const RollbackShape& s) {
    if (m.player >= s.players || m.frame < 0) return false;
    w.U8(m.player);
    w.Varint(static_cast<uint64_t>(m.frame));
    return true;
}
void Dec(Reader& r, RbFrozen& m, const RollbackShape& s) {
    m.player = r.U8();
    if (r.Ok() && m.player >= s.players) r.Fail(DecodeError::e_badValue);
    m.frame = r.Frame();
}

// No shape needed: the hello is how a receiver learns the sender's.
bool Enc(Writer& w, const RbHello& m, const RollbackShape&) {
    if (m.players < 1 || m.players > kRollbackMaxPlayers || m.inputBytes < 1 || m.inputBytes > kRollbackMaxInputBytes)
        return false;
    w.U32(m.determinismVersion);
    w.U8(m.players);
    w.Varint(m.inputBytes);
    return true;
}
void Dec(Reader& r, RbHello& m, const RollbackShape&) {
    m.determinismVersion = r.U32();
    m.players = r.U8();
    if (r.Ok() && (m.players < 1 || m.players > kRollbackMaxPlayers)) r.Fail(DecodeError::e_badValue);
    const uint64_t bytes = r.Varint();
    if (r.Ok() && (bytes < 1 || bytes > kRollbackMaxInputBytes)) r.Fail(DecodeError::e_badValue);
    m.inputBytes = static_cast<uint32_t>(bytes);
}

bool Enc(Writer& w, const RbDelayWish& m, const RollbackShape&) {
    if (m.frames > kRollbackMaxInputDelay) return false;
    w.U8(m.frames);
    return true;
}
void Dec(Reader& r, RbDelayWish& m, const RollbackShape&) {
    m.frames = r.U8();
    if (r.Ok() && m.frames > kRollbackMaxInputDelay) r.Fail(DecodeError::e_badValue);
}

// Input-carrying messages need a valid shape to be sized at all.
template <class M>
constexpr bool kNeedsShape = std::is_same_v<M, RbInputs> || std::is_same_v<M, RbInputAck> ||
                             std::is_same_v<M, RbConfirmed> || std::is_same_v<M, RbView> || std::is_same_v<M, RbFrozen>;

template <size_t I = 0>
bool DecodeIndexed(Reader& r, size_t index, const RollbackShape& s, RollbackMessage& out) {
    if constexpr (I < std::variant_size_v<RollbackMessage>) {
        if (index == I) {
            using M = std::variant_alternative_t<I, RollbackMessage>;
            if constexpr (kNeedsShape<M>) {
                if (!ShapeOk(s)) {
                    r.Fail(DecodeError::e_noShape);
                    return false;
                }
            }
            M m;
            Dec(r, m, s);
            if (!r.Ok()) return false;
            out = std::move(m);
            return true;
        }
        return DecodeIndexed<I + 1>(r, index, s, out);
    } else {
        r.Fail(DecodeError::e_badType);
        return false;
    }
}

}  // namespace

DecodeError DecodeRollbackDatagram(std::span<const uint8_t> datagram, const RollbackShape& shape,
                                   RollbackHeader& header, std::vector<RollbackMessage>& out) {
    out.clear();
    if (datagram.size() < kRollbackHeaderBytes + 1) return DecodeError::e_tooShort;
    Reader r(datagram);
    if (r.U16() != kRollbackMagic) return DecodeError::e_badMagic;
    header.version = r.U8();
    header.matchId = r.U32();
    if (header.version != kRollbackProtocolVersion) return DecodeError::e_badVersion;
    while (!r.AtEnd()) {
        const uint8_t type = r.U8();
        if (type < 1 || type >= static_cast<uint8_t>(RollbackMessageType::e_end)) {
            out.clear();
            return DecodeError::e_badType;
        }
        RollbackMessage m;
        if (!DecodeIndexed(r, static_cast<size_t>(type - 1), shape, m)) {
            out.clear();
            return r.Ok() ? DecodeError::e_badValue : r.Failure();
        }
        // A sender of another shape: what follows cannot be sized; the hello says why.
        if (const auto* hello = std::get_if<RbHello>(&m);
            hello != nullptr && ShapeOk(shape) &&
            (hello->players != shape.players || hello->inputBytes != shape.inputBytes)) {
            out.clear();
            out.push_back(std::move(m));
            return DecodeError::e_incompatible;
        }
        out.push_back(std::move(m));
    }
    return DecodeError::e_ok;
}

const char* RollbackIncompatibilityName(RollbackIncompatibility why) noexcept {
    switch (why) {
        case RollbackIncompatibility::e_none: return "none";
        case RollbackIncompatibility::e_protocolVersion: return "protocol version";
        case RollbackIncompatibility::e_matchId: return "match id";
        case RollbackIncompatibility::e_determinismVersion: return "determinism version";
        case RollbackIncompatibility::e_sessionShape: return "session shape";
    }
    return "unknown";
}

RollbackIncompatibility FindIncompatibility(DecodeError error, const RollbackHeader& header,
                                            std::span<const RollbackMessage> messages, uint32_t matchId,
                                            uint32_t determinismVersion) noexcept {
    if (error == DecodeError::e_badVersion) return RollbackIncompatibility::e_protocolVersion;
    if (error != DecodeError::e_ok && error != DecodeError::e_incompatible) return RollbackIncompatibility::e_none;
    if (header.matchId != matchId) return RollbackIncompatibility::e_matchId;
    for (const RollbackMessage& m : messages)
        if (const auto* hello = std::get_if<RbHello>(&m)) {
            if (hello->determinismVersion != determinismVersion) return RollbackIncompatibility::e_determinismVersion;
            if (error == DecodeError::e_incompatible) return RollbackIncompatibility::e_sessionShape;
        }
    return RollbackIncompatibility::e_none;
}

void RollbackDatagramWriter::Begin(const RollbackHeader& header) {
    m_bytes.clear();
    m_messages = 0;
    Writer w(m_bytes);
    w.U16(kRollbackMagic);
    w.U8(header.version);
    w.U32(header.matchId);
}

bool RollbackDatagramWriter::Add(const RollbackMessage& message, const RollbackShape& shape, size_t limit) {
    m_scratch.clear();
    Writer w(m_scratch);
    w.U8(static_cast<uint8_t>(message.index() + 1));
    const bool ok = std::visit(
        [&](const auto& m) {
            using M = std::decay_t<decltype(m)>;
            if constexpr (kNeedsShape<M>) {
                if (!ShapeOk(shape)) return false;
            }
            return Enc(w, m, shape);
        },
        message);
    if (!ok || m_bytes.size() + m_scratch.size() > limit) return false;
    m_bytes.insert(m_bytes.end(), m_scratch.begin(), m_scratch.end());
    ++m_messages;
    return true;
}

}  // namespace lockbox::net
