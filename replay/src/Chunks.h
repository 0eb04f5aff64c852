#pragma once
// Header and chunk framing (private): encoding, checksums and zstd.

#include <span>
#include <vector>

#include "lockbox/replay/Format.h"

namespace lockbox::replay::detail {

/// Appends the 60-byte header with its checksum.
void EncodeHeader(const Header& h, std::vector<uint8>& out);
/// Reads and checks the header at the start of bytes (error offsets are file offsets).
Error DecodeHeader(std::span<const uint8> bytes, Header& h);

/// Appends one chunk: compressed with zstd at `level` when that is smaller (level <= 0:
/// stored raw).
void EncodeChunk(uint32 type, std::span<const uint8> raw, int level, std::vector<uint8>& out);

/// One chunk read from a file.
struct RawChunk {
    uint32 type = 0;
    uint32 flags = 0;
    uint64 offset = 0;       ///< of the chunk frame in the file
    uint32 storedBytes = 0;  ///< payload bytes in the file
    uint32 rawBytes = 0;     ///< payload bytes once decompressed
};

/// Reads the chunk frame at `offset`, checks its checksum and decompresses the payload into
/// `payload`. On success `offset` moves past the chunk.
Error ReadChunk(std::span<const uint8> file, uint64& offset, int32 index, RawChunk& chunk, std::vector<uint8>& payload);

}  // namespace lockbox::replay::detail
