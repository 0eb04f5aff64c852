// Header and chunk framing: little-endian fields, XXH3-64 checksums, zstd payloads.
#include "Chunks.h"

#include <xxhash.h>
// LOCKBOX_REPLAY_ZSTD=0 builds a reader and writer without zstd (tests/cross/run.sh, whose
// cross toolchains have no zstd library): chunks are then written raw, and a compressed chunk
// is refused with an error that says why.
#ifndef LOCKBOX_REPLAY_ZSTD
#define LOCKBOX_REPLAY_ZSTD 1
#endif
#if LOCKBOX_REPLAY_ZSTD
#include <zstd.h>
#endif

#include "lockbox/common/Bytes.h"

namespace lockbox::replay::detail {
namespace {

// Header bytes covered by its checksum (everything before the checksum field).
constexpr size_t kHeaderCovered = kHeaderBytes - 8;

uint64 ChunkChecksum(std::span<const uint8> frame16, std::span<const uint8> stored) {
    // The frame's first 16 bytes seed the payload hash, so a flipped type, flag or size is
    // caught as surely as a flipped payload byte.
    const uint64 seed = XXH3_64bits(frame16.data(), frame16.size());
    return XXH3_64bits_withSeed(stored.data(), stored.size(), seed);
}

Error Fail(ErrorCode code, uint64 offset, int32 index, uint32 type, std::string message) {
    Error e;
    e.code = code;
    e.offset = offset;
    e.chunkIndex = index;
    e.chunkType = type;
    e.message = std::move(message);
    return e;
}

}  // namespace

void EncodeHeader(const Header& h, std::vector<uint8>& out) {
    const size_t start = out.size();
    bytes::Writer w(out);
    w.U32(kMagic);
    w.U16(h.formatVersion);
    w.U16(static_cast<uint16>(kHeaderBytes));
    w.U16(h.engineMajor);
    w.U16(h.engineMinor);
    w.U16(h.enginePatch);
    w.U16(h.snapshotFormatVersion);
    w.U32(h.determinismVersion);
    w.U16(h.tickRate);
    w.U16(h.velocityIterations);
    w.U16(h.positionIterations);
    w.U16(h.playerCount);
    w.I32(h.timeStepRaw);
    w.U32(h.worldFlags);
    w.U16(h.inputBytes);
    w.U16(0);
    w.U32(h.hashInterval);
    w.U32(h.keyframeInterval);
    w.U32(h.reserved);
    w.U64(XXH3_64bits(out.data() + start, kHeaderCovered));
}

Error DecodeHeader(std::span<const uint8> bytes, Header& h) {
    // A short file that does not start like a replay is foreign, not truncated.
    const size_t prefix = bytes.size() < 4 ? bytes.size() : 4;
    for (size_t i = 0; i < prefix; ++i)
        if (bytes[i] != static_cast<uint8>(kMagic >> (8 * i)))
            return Fail(ErrorCode::e_badMagic, 0, -1, 0, "not a lockbox replay (magic is not \"LBRP\")");
    if (bytes.size() < 8)
        return Fail(ErrorCode::e_truncated, 0, -1, 0,
                    "file has " + std::to_string(bytes.size()) + " bytes, fewer than the 8-byte header start");
    bytes::Reader r(bytes);
    (void)r.U32();
    h.formatVersion = r.U16();
    const uint16 headerBytes = r.U16();
    if (h.formatVersion != kFormatVersion)
        return Fail(ErrorCode::e_badVersion, 4, -1, 0,
                    "format version " + std::to_string(h.formatVersion) + "; this reader reads version " +
                        std::to_string(kFormatVersion) + (h.formatVersion > kFormatVersion ? " (file is newer)" : ""));
    if (headerBytes != kHeaderBytes)
        return Fail(ErrorCode::e_badChunk, 6, -1, 0, "header size " + std::to_string(headerBytes) + ", expected 60");
    if (bytes.size() < kHeaderBytes)
        return Fail(ErrorCode::e_truncated, 0, -1, 0, "file ends inside the 60-byte header");
    h.engineMajor = r.U16();
    h.engineMinor = r.U16();
    h.enginePatch = r.U16();
    h.snapshotFormatVersion = r.U16();
    h.determinismVersion = r.U32();
    h.tickRate = r.U16();
    h.velocityIterations = r.U16();
    h.positionIterations = r.U16();
    h.playerCount = r.U16();
    h.timeStepRaw = r.I32();
    h.worldFlags = r.U32();
    h.inputBytes = r.U16();
    (void)r.U16();
    h.hashInterval = r.U32();
    h.keyframeInterval = r.U32();
    h.reserved = r.U32();
    const uint64 sum = r.U64();
    if (sum != XXH3_64bits(bytes.data(), kHeaderCovered))
        return Fail(ErrorCode::e_badChecksum, 52, -1, 0, "header checksum does not match");
    if (h.playerCount < 1 || h.playerCount > kMaxPlayers)
        return Fail(ErrorCode::e_badChunk, 26, -1, 0,
                    "player count " + std::to_string(h.playerCount) + " outside 1..64");
    if (h.inputBytes > kMaxInputBytes)
        return Fail(ErrorCode::e_badChunk, 36, -1, 0, "input size " + std::to_string(h.inputBytes) + " above 1024");
    if (h.hashInterval < 1) return Fail(ErrorCode::e_badChunk, 40, -1, 0, "hash interval 0");
    if (h.timeStepRaw < 0) return Fail(ErrorCode::e_badChunk, 28, -1, 0, "negative time step");
    if (h.tickRate < 1) return Fail(ErrorCode::e_badChunk, 20, -1, 0, "tick rate 0");
    return {};
}

void EncodeChunk(uint32 type, std::span<const uint8> raw, int level, std::vector<uint8>& out) {
    std::vector<uint8> packed;
    uint32 flags = 0;
#if LOCKBOX_REPLAY_ZSTD
    if (level > 0 && raw.size() > 32) {
        packed.resize(ZSTD_compressBound(raw.size()));
        const size_t n = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), level);
        if (!ZSTD_isError(n) && n < raw.size()) {
            packed.resize(n);
            flags |= kChunkCompressed;
        }
    }
#else
    (void)level;
#endif
    const std::span<const uint8> stored = (flags & kChunkCompressed) ? std::span<const uint8>(packed) : raw;
    const size_t start = out.size();
    bytes::Writer w(out);
    w.U32(type);
    w.U32(flags);
    w.U32(static_cast<uint32>(stored.size()));
    w.U32(static_cast<uint32>(raw.size()));
    const uint64 sum = ChunkChecksum(std::span<const uint8>(out.data() + start, 16), stored);
    w.U64(sum);
    w.Bytes(stored);
}

Error ReadChunk(std::span<const uint8> file, uint64& offset, int32 index, RawChunk& chunk,
                std::vector<uint8>& payload) {
    chunk = RawChunk{};
    chunk.offset = offset;
    if (file.size() - offset < kChunkHeaderBytes)
        return Fail(ErrorCode::e_truncated, offset, index, 0,
                    "file ends inside a chunk header (" + std::to_string(file.size() - offset) + " of 24 bytes)");
    bytes::Reader r(file.subspan(offset, kChunkHeaderBytes));
    chunk.type = r.U32();
    chunk.flags = r.U32();
    chunk.storedBytes = r.U32();
    chunk.rawBytes = r.U32();
    const uint64 sum = r.U64();
    const uint64 payloadStart = offset + kChunkHeaderBytes;
    if (chunk.storedBytes > file.size() - payloadStart)
        return Fail(ErrorCode::e_truncated, offset, index, chunk.type,
                    "chunk announces " + std::to_string(chunk.storedBytes) + " payload bytes, the file has " +
                        std::to_string(file.size() - payloadStart));
    const std::span<const uint8> stored = file.subspan(payloadStart, chunk.storedBytes);
    if (sum != ChunkChecksum(file.subspan(offset, 16), stored))
        return Fail(ErrorCode::e_badChecksum, offset, index, chunk.type, "chunk checksum does not match");
    if (chunk.rawBytes > kMaxChunkBytes)
        return Fail(ErrorCode::e_badChunk, offset, index, chunk.type,
                    "raw size " + std::to_string(chunk.rawBytes) + " above the 256 MiB limit");
    if ((chunk.flags & ~kChunkCompressed) != 0)
        return Fail(ErrorCode::e_badChunk, offset, index, chunk.type, "unknown chunk flags");
    if (chunk.flags & kChunkCompressed) {
#if !LOCKBOX_REPLAY_ZSTD
        return Fail(ErrorCode::e_badChunk, offset, index, chunk.type,
                    "compressed chunk, but this build has no zstd (LOCKBOX_REPLAY_ZSTD=0): record with --level 0");
#else
        payload.resize(chunk.rawBytes);
        const size_t n = ZSTD_decompress(payload.data(), payload.size(), stored.data(), stored.size());
        if (ZSTD_isError(n) || n != chunk.rawBytes)
            return Fail(ErrorCode::e_badChunk, offset, index, chunk.type,
                        std::string("zstd payload does not decompress to the announced size") +
                            (ZSTD_isError(n) ? std::string(" (") + ZSTD_getErrorName(n) + ")" : std::string()));
#endif
    } else {
        if (chunk.rawBytes != chunk.storedBytes)
            return Fail(ErrorCode::e_badChunk, offset, index, chunk.type,
                        "uncompressed chunk with raw size != stored size");
        payload.assign(stored.begin(), stored.end());
    }
    offset = payloadStart + chunk.storedBytes;
    return {};
}

}  // namespace lockbox::replay::detail
