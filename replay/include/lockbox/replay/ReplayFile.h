#pragma once
/// @file
/// A replay read into memory and validated (ParseReplay, LoadReplay): the header, the game's
/// name and parameters, the seed, every frame's inputs, the stored hashes, the keyframes and
/// the chunk statistics. Unknown chunk types are skipped (counted in unknownChunks).

#include <span>
#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/replay/Format.h"

namespace lockbox::replay {

/// A stored snapshot: the seed (frame 0) or a keyframe.
struct Keyframe {
    int32 frame = 0;           ///< frames simulated before this state (0: the seed)
    uint64 hash = 0;           ///< b2World::Hash of the state when it was recorded
    std::vector<uint8> world;  ///< b2World::Save image
    std::vector<uint8> user;   ///< Game::SaveUserState bytes
};

/// Count and sizes of one chunk type in a file.
struct ChunkStat {
    /// The chunk type (a ChunkType tag such as META or INPT, see ChunkTag).
    uint32 type = 0;
    /// How many chunks of this type the file holds.
    uint32 count = 0;
    uint64 storedBytes = 0;  ///< in the file, chunk frames included
    uint64 rawBytes = 0;     ///< payloads once decompressed
};

/// A whole replay.
struct LOCKBOX_API ReplayFile {
    /// The fixed header (format and engine versions, step settings, session shape).
    Header header;
    std::string gameName;               ///< what the player must build (e.g. "scene:rain")
    std::vector<uint8> gameParams;      ///< the game's own parameters
    Keyframe seed;                      ///< the state before frame 0
    int32 frameCount = 0;               ///< frames recorded (the END record's count)
    std::vector<uint8> inputs;          ///< frameCount * playerCount * inputBytes
    std::vector<uint64> hashes;         ///< by frame: state hash after that frame (0 if not stored)
    std::vector<uint8> hashStored;      ///< by frame: 1 where hashes[] holds a stored hash
    std::vector<uint64> stageHashes;    ///< frameCount * kStagesPerFrame, or empty
    std::vector<uint64> solveHashes;    ///< frameCount * kSolvePhasesPerFrame, or empty
    std::vector<Keyframe> keyframes;    ///< increasing frame order, seed excluded
    uint64 finalHash = 0;               ///< hash after the last frame (END record)
    std::vector<ChunkStat> chunkStats;  ///< by first appearance
    /// Size of the whole file, bytes.
    uint64 fileBytes = 0;
    uint32 unknownChunks = 0;  ///< chunks of types this reader does not know (skipped)

    /// Bytes per frame of inputs (all players).
    size_t FrameInputBytes() const noexcept { return static_cast<size_t>(header.playerCount) * header.inputBytes; }
    /// Frame `frame`'s inputs (all players); empty outside [0, frameCount).
    std::span<const uint8> Inputs(int32 frame) const noexcept;
    /// True when a hash after frame `frame` is stored.
    bool HasHash(int32 frame) const noexcept {
        return frame >= 0 && frame < frameCount && hashStored[static_cast<size_t>(frame)] != 0;
    }
    /// Stored fencepost hashes of frame `frame` (kStagesPerFrame values), or nullptr.
    const uint64* Stages(int32 frame) const noexcept;
    /// Stored solve-phase hashes of frame `frame` (kSolvePhasesPerFrame values), or nullptr.
    const uint64* SolvePhases(int32 frame) const noexcept;
    /// The latest stored state at or before `frame` frames: a keyframe or the seed.
    const Keyframe& NearestKeyframe(int32 frame) const noexcept;
};

/// Parses and validates a whole file image. On error `out` is unspecified.
LOCKBOX_API Error ParseReplay(std::span<const uint8> bytes, ReplayFile& out);
/// Reads a file and parses it.
LOCKBOX_API Error LoadReplay(const std::string& path, ReplayFile& out);
/// Reads a whole file into bytes.
LOCKBOX_API Error ReadFileBytes(const std::string& path, std::vector<uint8>& bytes);

}  // namespace lockbox::replay
