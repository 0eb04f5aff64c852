// ParseReplay: header, then every chunk in order, checked for sequence and size before use.
#include <algorithm>
#include <cstdio>

#include "Chunks.h"
#include "lockbox/common/Bytes.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/state/Snapshot.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::replay {

std::span<const uint8> ReplayFile::Inputs(int32 frame) const noexcept {
    if (frame < 0 || frame >= frameCount) return {};
    const size_t n = FrameInputBytes();
    return std::span<const uint8>(inputs.data() + static_cast<size_t>(frame) * n, n);
}

namespace {
const uint64* PerFrame(const std::vector<uint64>& all, int32 frame, int32 frameCount, uint32 per) noexcept {
    if (frame < 0 || frame >= frameCount) return nullptr;
    const size_t at = static_cast<size_t>(frame) * per;
    return at + per <= all.size() ? all.data() + at : nullptr;
}
}  // namespace

const uint64* ReplayFile::Stages(int32 frame) const noexcept {
    return PerFrame(stageHashes, frame, frameCount, kStagesPerFrame);
}

const uint64* ReplayFile::SolvePhases(int32 frame) const noexcept {
    return PerFrame(solveHashes, frame, frameCount, kSolvePhasesPerFrame);
}

const Keyframe& ReplayFile::NearestKeyframe(int32 frame) const noexcept {
    const Keyframe* best = &seed;
    for (const Keyframe& k : keyframes)
        if (k.frame <= frame) best = &k;
    return *best;
}

namespace {

struct Parser {
    explicit Parser(ReplayFile& file) : out(file) {}
    ReplayFile& out;
    detail::RawChunk chunk;
    int32 index = 0;
    int32 inputFrames = 0;
    int32 stageFrames = 0;
    int32 solveFrames = 0;
    bool haveMeta = false, haveSeed = false, haveEnd = false;

    Error Fail(ErrorCode code, int32 frame, std::string message) const {
        Error e;
        e.code = code;
        e.offset = chunk.offset;
        e.chunkIndex = index;
        e.chunkType = chunk.type;
        e.frame = frame;
        e.message = std::move(message);
        return e;
    }

    // A block of per-frame hashes (STAG, SOLV): {first frame, count, values per frame, values}.
    Error FrameHashes(bytes::Reader& r, const char* name, uint32 expectPer, int32& framesSoFar,
                      std::vector<uint64>& into) const {
        const uint32 first = r.U32();
        const uint32 count = r.U32();
        const uint32 per = r.U32();
        if (!r.Ok() || per != expectPer || static_cast<uint64>(count) * per * 8 != r.Remaining())
            return Fail(ErrorCode::e_badChunk, -1, std::string(name) + " chunk sizes do not add up");
        if (first != static_cast<uint32>(framesSoFar) ||
            static_cast<uint64>(first) + count > static_cast<uint64>(inputFrames))
            return Fail(ErrorCode::e_badChunk, static_cast<int32>(std::min<uint32>(first, INT32_MAX)),
                        std::string(name) + " hashes out of sequence");
        for (uint64 i = 0; i < static_cast<uint64>(count) * per; ++i) into.push_back(r.U64());
        framesSoFar += static_cast<int32>(count);
        return {};
    }

    Error Snapshot(bytes::Reader& r, Keyframe& k) {
        k.frame = r.I32();
        k.hash = r.U64();
        const auto world = r.Blob();
        const auto user = r.Blob();
        if (!r.Ok() || r.Remaining() != 0) return Fail(ErrorCode::e_badChunk, -1, "snapshot chunk sizes do not add up");
        k.world.assign(world.begin(), world.end());
        k.user.assign(user.begin(), user.end());
        return {};
    }

    Error Chunk(std::span<const uint8> payload) {
        bytes::Reader r(payload);
        const size_t frameBytes = out.FrameInputBytes();
        if (!haveMeta && chunk.type != e_chunkMeta)
            return Fail(ErrorCode::e_missing, -1, "the first chunk must be META");
        if (haveEnd) return Fail(ErrorCode::e_badChunk, -1, "chunk after the END record");
        switch (chunk.type) {
            case e_chunkMeta: {
                if (haveMeta) return Fail(ErrorCode::e_badChunk, -1, "second META chunk");
                const auto name = r.Bytes(r.U16());
                const auto params = r.Blob();
                if (!r.Ok() || r.Remaining() != 0) return Fail(ErrorCode::e_badChunk, -1, "META sizes do not add up");
                out.gameName.assign(name.begin(), name.end());
                out.gameParams.assign(params.begin(), params.end());
                haveMeta = true;
                return {};
            }
            case e_chunkSeed: {
                if (haveSeed) return Fail(ErrorCode::e_badChunk, 0, "second SEED chunk");
                if (Error e = Snapshot(r, out.seed); !e.ok()) return e;
                if (out.seed.frame != 0) return Fail(ErrorCode::e_badChunk, out.seed.frame, "seed frame is not 0");
                haveSeed = true;
                return {};
            }
            case e_chunkInputs: {
                if (!haveSeed) return Fail(ErrorCode::e_missing, inputFrames, "inputs before the SEED chunk");
                const uint32 first = r.U32();
                const uint32 count = r.U32();
                if (!r.Ok())
                    return Fail(ErrorCode::e_badChunk, inputFrames, "INPT chunk shorter than its 8-byte prefix");
                if (first != static_cast<uint32>(inputFrames))
                    return Fail(ErrorCode::e_badChunk, static_cast<int32>(first),
                                "input block starts at frame " + std::to_string(first) + ", expected " +
                                    std::to_string(inputFrames));
                if (count > kMaxChunkBytes || static_cast<uint64>(count) * frameBytes != r.Remaining() ||
                    count > static_cast<uint32>(INT32_MAX - inputFrames))
                    return Fail(ErrorCode::e_badChunk, inputFrames,
                                "input block of " + std::to_string(count) + " frames has " +
                                    std::to_string(r.Remaining()) + " bytes");
                if (count > kMaxFrames - static_cast<uint32>(inputFrames))
                    return Fail(ErrorCode::e_badChunk, inputFrames,
                                "input block of " + std::to_string(count) + " frames would take the replay past " +
                                    std::to_string(kMaxFrames) + " frames");
                const auto bytes = r.Bytes(r.Remaining());
                out.inputs.insert(out.inputs.end(), bytes.begin(), bytes.end());
                inputFrames += static_cast<int32>(count);
                out.hashes.resize(static_cast<size_t>(inputFrames), 0);
                out.hashStored.resize(static_cast<size_t>(inputFrames), 0);
                return {};
            }
            case e_chunkHashes: {
                const uint32 first = r.U32();
                const uint32 count = r.U32();
                const uint64 interval = out.header.hashInterval;
                if (!r.Ok() || static_cast<uint64>(count) * 8 != r.Remaining())
                    return Fail(ErrorCode::e_badChunk, -1, "HASH chunk sizes do not add up");
                if (count == 0) return {};
                const uint64 last = first + (static_cast<uint64>(count) - 1) * interval;
                if ((static_cast<uint64>(first) + 1) % interval != 0 || last >= static_cast<uint64>(inputFrames))
                    return Fail(ErrorCode::e_badChunk, static_cast<int32>(std::min<uint64>(first, INT32_MAX)),
                                "hashes for frames " + std::to_string(first) + ".." + std::to_string(last) +
                                    " do not fit the interval or the " + std::to_string(inputFrames) +
                                    " frames of inputs so far");
                for (uint32 i = 0; i < count; ++i) {
                    const size_t f = static_cast<size_t>(first + i * interval);
                    out.hashes[f] = r.U64();
                    out.hashStored[f] = 1;
                }
                return {};
            }
            case e_chunkStages: return FrameHashes(r, "STAG", kStagesPerFrame, stageFrames, out.stageHashes);
            case e_chunkSolve: return FrameHashes(r, "SOLV", kSolvePhasesPerFrame, solveFrames, out.solveHashes);
            case e_chunkKeyframe: {
                Keyframe k;
                if (Error e = Snapshot(r, k); !e.ok()) return e;
                const int32 previous = out.keyframes.empty() ? 0 : out.keyframes.back().frame;
                if (k.frame <= previous || k.frame > inputFrames)
                    return Fail(ErrorCode::e_badChunk, k.frame,
                                "keyframe at frame " + std::to_string(k.frame) + " is out of order (previous " +
                                    std::to_string(previous) + ", inputs so far " + std::to_string(inputFrames) + ")");
                out.keyframes.push_back(std::move(k));
                return {};
            }
            case e_chunkEnd: {
                const int32 frames = r.I32();
                out.finalHash = r.U64();
                if (!r.Ok() || r.Remaining() != 0) return Fail(ErrorCode::e_badChunk, -1, "END sizes do not add up");
                if (frames != inputFrames)
                    return Fail(ErrorCode::e_badChunk, frames,
                                "END record counts " + std::to_string(frames) + " frames, the inputs hold " +
                                    std::to_string(inputFrames));
                if (stageFrames != 0 && stageFrames != inputFrames)
                    return Fail(ErrorCode::e_badChunk, stageFrames, "stage hashes stop before the last frame");
                if (solveFrames != 0 && solveFrames != inputFrames)
                    return Fail(ErrorCode::e_badChunk, solveFrames, "solve-phase hashes stop before the last frame");
                out.frameCount = frames;
                haveEnd = true;
                return {};
            }
            default:
                // A chunk type from a later writer: its frame says how far to skip.
                ++out.unknownChunks;
                return {};
        }
    }
};

}  // namespace

Error ParseReplay(std::span<const uint8> bytes, ReplayFile& out) {
    out = ReplayFile{};
    out.fileBytes = bytes.size();
    if (Error e = detail::DecodeHeader(bytes, out.header); !e.ok()) return e;
    const Header& h = out.header;
    // Snapshots of an older format that Restore still reads replay the same bits (format 2
    // only added the joints' reaction directions, which no step reads).
    const bool snapshotsReadable =
        h.snapshotFormatVersion >= b2_snapshotOldestReadable && h.snapshotFormatVersion <= b2_snapshotFormatVersion;
    if (h.determinismVersion != b2_determinismVersion || !snapshotsReadable) {
        Error e;
        e.code = ErrorCode::e_badEngine;
        e.offset = 14;
        e.message = "recorded with determinism version 0x" +
                    [&] {
                        char buf[16];
                        std::snprintf(buf, sizeof buf, "%08x", h.determinismVersion);
                        return std::string(buf);
                    }() +
                    " and snapshot format " + std::to_string(h.snapshotFormatVersion) + "; this engine has 0x" +
                    [] {
                        char buf[16];
                        std::snprintf(buf, sizeof buf, "%08x", b2_determinismVersion);
                        return std::string(buf);
                    }() +
                    " and reads snapshot formats " + std::to_string(b2_snapshotOldestReadable) + " to " +
                    std::to_string(b2_snapshotFormatVersion);
        return e;
    }
    Parser p(out);
    uint64 offset = kHeaderBytes;
    std::vector<uint8> payload;
    while (offset < bytes.size()) {
        if (Error e = detail::ReadChunk(bytes, offset, p.index, p.chunk, payload); !e.ok()) {
            e.frame = p.inputFrames;
            return e;
        }
        auto stat = std::find_if(out.chunkStats.begin(), out.chunkStats.end(),
                                 [&](const ChunkStat& s) { return s.type == p.chunk.type; });
        if (stat == out.chunkStats.end()) stat = out.chunkStats.insert(out.chunkStats.end(), ChunkStat{p.chunk.type});
        ++stat->count;
        stat->storedBytes += kChunkHeaderBytes + p.chunk.storedBytes;
        stat->rawBytes += p.chunk.rawBytes;
        if (Error e = p.Chunk(payload); !e.ok()) return e;
        ++p.index;
    }
    Error e;
    e.offset = bytes.size();
    e.chunkIndex = p.index;
    e.frame = p.inputFrames;
    if (!p.haveMeta || !p.haveSeed) {
        e.code = ErrorCode::e_missing;
        e.message = !p.haveMeta ? "no META chunk" : "no SEED chunk";
        return e;
    }
    if (!p.haveEnd) {
        e.code = ErrorCode::e_truncated;
        e.message = "file ends after frame " + std::to_string(p.inputFrames) + " without an END record";
        return e;
    }
    return {};
}

Error ReadFileBytes(const std::string& path, std::vector<uint8>& bytes) {
    Error e;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) {
        e.code = ErrorCode::e_io;
        e.message = "cannot open " + path;
        return e;
    }
    bytes.clear();
    uint8 buffer[1 << 16];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    const bool bad = std::ferror(f) != 0;
    std::fclose(f);
    if (bad) {
        e.code = ErrorCode::e_io;
        e.message = "read error on " + path;
    }
    return e;
}

Error LoadReplay(const std::string& path, ReplayFile& out) {
    std::vector<uint8> bytes;
    if (Error e = ReadFileBytes(path, bytes); !e.ok()) return e;
    return ParseReplay(bytes, out);
}

}  // namespace lockbox::replay
