// libFuzzer target for the replay reader and player, structure-aware. A byte-level mutator
// rarely gets past a replay's checksums and zstd frames, so most inputs die at the framing and
// the chunk decoders behind it are never reached. The custom mutator below decodes a valid
// file into its header and chunks, changes one thing at the level of the format (a chunk's
// decompressed payload, a header field, the order or number of chunks, the frame count), and
// writes the file again with fresh compression and checksums. One mutation in eight stays at
// byte level without resealing, so the framing and checksum checks keep their coverage.
//
// Every input must parse or be refused with an error, never crash, hang or allocate without
// bound. A file that parses and names a library scene is played: verified whole when it is
// short, otherwise from each keyframe for a few frames (keyframe snapshots go through
// b2World::Restore's own validation). Seed corpus: tests/golden/replays.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "../replay/src/Chunks.h"
#include "lockbox/common/Bytes.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t maxSize);

namespace {

using namespace lockbox;
using namespace lockbox::replay;

// Frames a short replay may have to be verified whole, and frames played after each keyframe
// of a longer one: enough to reach the player's paths, few enough to keep executions fast.
constexpr int32 kVerifyFrames = 32;
constexpr int32 kFramesPerKeyframe = 4;
// Largest decompressed payload a mutation may grow a chunk to.
constexpr size_t kMaxMutatedPayload = 1u << 16;

struct Chunk {
    uint32 type = 0;
    std::vector<uint8> raw;
};

struct Decoded {
    Header header;
    std::vector<Chunk> chunks;
};

bool Decode(std::span<const uint8> bytes, Decoded& out) {
    if (!replay::detail::DecodeHeader(bytes, out.header).ok()) return false;
    uint64 offset = kHeaderBytes;
    replay::detail::RawChunk raw;
    std::vector<uint8> payload;
    for (int32 index = 0; offset < bytes.size(); ++index) {
        if (!replay::detail::ReadChunk(bytes, offset, index, raw, payload).ok()) return false;
        out.chunks.push_back({raw.type, payload});
    }
    return true;
}

std::vector<uint8> Encode(const Decoded& d, int level) {
    std::vector<uint8> out;
    replay::detail::EncodeHeader(d.header, out);
    for (const Chunk& c : d.chunks) replay::detail::EncodeChunk(c.type, c.raw, level, out);
    return out;
}

// A value a reader's size and range checks care about: small, at a boundary, or any.
uint32 InterestingU32(std::minstd_rand& rng) {
    static constexpr uint32 kValues[] = {0,  1,   2,   3,    7,    8,           60,          63,         64,
                                         65, 255, 256, 1024, 1025, 0x7fffffffu, 0x80000000u, 0xffffffffu};
    if (rng() % 2 == 0) return kValues[rng() % std::size(kValues)];
    return static_cast<uint32>(rng()) ^ (static_cast<uint32>(rng()) << 16);
}

void MutateHeader(Header& h, std::minstd_rand& rng) {
    const uint32 v = InterestingU32(rng);
    switch (rng() % 11) {
        case 0: h.tickRate = static_cast<uint16>(v); break;
        case 1: h.timeStepRaw = static_cast<int32>(v); break;
        case 2: h.velocityIterations = static_cast<uint16>(v % 64); break;
        case 3: h.positionIterations = static_cast<uint16>(v % 64); break;
        case 4: h.worldFlags = v; break;
        case 5: h.playerCount = static_cast<uint16>(v); break;
        case 6: h.inputBytes = static_cast<uint16>(v); break;
        case 7: h.hashInterval = v; break;
        case 8: h.keyframeInterval = v; break;
        case 9: h.snapshotFormatVersion = static_cast<uint16>(v % 4); break;
        default: h.reserved = v; break;
    }
}

// Overwrites a little-endian field of a payload, if the payload is long enough to hold it.
void PutU32(std::vector<uint8>& raw, size_t at, uint32 value) {
    if (raw.size() < at + 4) return;
    for (size_t i = 0; i < 4; ++i) raw[at + i] = static_cast<uint8>(value >> (8 * i));
}

// Cuts the replay to `frames` frames: input blocks shortened or dropped past the cut, hash,
// stage and keyframe chunks beyond it dropped, the END record's count rewritten. This is how
// the player's paths are reached from long seeds within a few frames.
void CutFrames(Decoded& d, uint32 frames) {
    const size_t frameBytes = static_cast<size_t>(d.header.playerCount) * d.header.inputBytes;
    std::vector<Chunk> kept;
    for (Chunk& c : d.chunks) {
        bytes::Reader r(c.raw);
        switch (c.type) {
            case e_chunkInputs: {
                const uint32 first = r.U32();
                const uint32 count = r.U32();
                if (!r.Ok() || first >= frames) continue;
                const uint32 keep = std::min(count, frames - first);
                c.raw.resize(std::min<size_t>(c.raw.size(), 8 + keep * frameBytes));
                PutU32(c.raw, 4, keep);
                break;
            }
            case e_chunkHashes: {
                // {first, count, hashes}: hashes after frames first, first + interval, ...
                const uint32 first = r.U32();
                const uint32 count = r.U32();
                if (!r.Ok() || first >= frames) continue;
                const uint32 interval = std::max<uint32>(d.header.hashInterval, 1);
                const uint32 keep = std::min(count, (frames - 1 - first) / interval + 1);
                c.raw.resize(std::min<size_t>(c.raw.size(), 8 + size_t{keep} * 8));
                PutU32(c.raw, 4, keep);
                break;
            }
            case e_chunkStages:
            case e_chunkSolve: {
                // {first, count, values per frame, values}.
                const uint32 first = r.U32();
                const uint32 count = r.U32();
                const uint32 per = r.U32();
                if (!r.Ok() || first >= frames) continue;
                const uint32 keep = std::min(count, frames - first);
                c.raw.resize(std::min<size_t>(c.raw.size(), 12 + size_t{keep} * per * 8));
                PutU32(c.raw, 4, keep);
                break;
            }
            case e_chunkKeyframe: {
                const int32 frame = r.I32();
                if (!r.Ok() || frame < 0 || static_cast<uint32>(frame) > frames) continue;
                break;
            }
            case e_chunkEnd: {
                PutU32(c.raw, 0, frames);
                break;
            }
            default: break;
        }
        kept.push_back(std::move(c));
    }
    d.chunks = std::move(kept);
}

void MutateChunks(Decoded& d, std::minstd_rand& rng) {
    static constexpr uint32 kTypes[] = {e_chunkMeta,     e_chunkSeed,   e_chunkInputs,
                                        e_chunkHashes,   e_chunkStages, e_chunkSolve,
                                        e_chunkKeyframe, e_chunkEnd,    ChunkTag('N', 'E', 'W', '?')};
    std::vector<Chunk>& chunks = d.chunks;
    const size_t n = chunks.size();
    switch (rng() % 6) {
        case 0:
            if (n > 0) chunks.erase(chunks.begin() + static_cast<std::ptrdiff_t>(rng() % n));
            break;
        case 1:
            if (n > 0) chunks.insert(chunks.begin() + static_cast<std::ptrdiff_t>(rng() % n), chunks[rng() % n]);
            break;
        case 2:
            if (n > 1) std::swap(chunks[rng() % n], chunks[rng() % n]);
            break;
        case 3:
            if (n > 0) chunks[rng() % n].type = kTypes[rng() % std::size(kTypes)];
            break;
        case 4: {
            Chunk c{kTypes[rng() % std::size(kTypes)], std::vector<uint8>(rng() % 64)};
            for (uint8& b : c.raw) b = static_cast<uint8>(rng());
            chunks.insert(chunks.begin() + static_cast<std::ptrdiff_t>(n == 0 ? 0 : rng() % (n + 1)), std::move(c));
            break;
        }
        default: CutFrames(d, 1 + static_cast<uint32>(rng() % kVerifyFrames)); break;
    }
}

void MutatePayload(Decoded& d, std::minstd_rand& rng) {
    if (d.chunks.empty()) return;
    std::vector<uint8>& raw = d.chunks[rng() % d.chunks.size()].raw;
    const size_t size = raw.size();
    raw.resize(std::min(kMaxMutatedPayload, size * 2 + 16));
    raw.resize(LLVMFuzzerMutate(raw.data(), size, raw.size()));
}

}  // namespace

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t maxSize, unsigned int seed) {
    std::minstd_rand rng(seed == 0 ? 1 : seed);
    Decoded d;
    if (rng() % 8 == 0 || !Decode(std::span<const uint8>(data, size), d)) return LLVMFuzzerMutate(data, size, maxSize);
    const int mutations = 1 + static_cast<int>(rng() % 3);
    for (int i = 0; i < mutations; ++i) {
        switch (rng() % 3) {
            case 0: MutatePayload(d, rng); break;
            case 1: MutateChunks(d, rng); break;
            default: MutateHeader(d.header, rng); break;
        }
    }
    const std::vector<uint8> out = Encode(d, static_cast<int>(rng() % 4));
    if (out.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
    std::copy(out.begin(), out.end(), data);
    return out.size();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    ReplayFile file;
    if (!ParseReplay(std::span<const uint8>(data, size), file).ok()) return 0;
    (void)file.NearestKeyframe(file.frameCount);
    const std::string scene = SceneGame::SceneName(file.gameName);
    if (scene.empty()) return 0;
    SceneGame game(scene);
    if (!game.ok()) return 0;
    Player player(file, game.world(), game);
    if (file.frameCount <= kVerifyFrames) {
        (void)player.Verify();
        return 0;
    }
    for (const Keyframe& k : file.keyframes) {
        if (!player.Restore(k).ok()) continue;
        for (int32 i = 0; i < kFramesPerKeyframe && player.Step(); ++i) {
        }
    }
    return 0;
}
