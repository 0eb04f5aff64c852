#pragma once
/// @file
/// Replay file format (docs/replay.md "File format"): a fixed header, then
/// self-describing chunks. Every integer is little-endian with a fixed width. Each chunk
/// carries its type, a flag word (bit 0: the payload is zstd-compressed), the stored and raw
/// payload sizes and an XXH3-64 checksum, so an older reader skips a chunk type it does not
/// know and a damaged chunk is detected before it is used.

#include <array>
#include <cstddef>
#include <string>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"

/// The replay module: recording a match's inputs and hashes into a replay file, playing it back,
/// verifying it, and locating the first divergence between two runs (diff and bisect).
namespace lockbox::replay {

/// The four bytes that open every replay file: "LBRP".
inline constexpr uint32 kMagic = 0x5052424Cu;  // 'L' 'B' 'R' 'P', low byte first
/// Version of this file layout; a reader refuses a newer one (and an older one it cannot read).
inline constexpr uint16 kFormatVersion = 1;
/// Bytes of the version-1 header, checksum included.
inline constexpr uint32 kHeaderBytes = 60;
/// Bytes of a chunk's frame: type, flags, stored size, raw size (4 bytes each), checksum (8).
inline constexpr uint32 kChunkHeaderBytes = 24;
/// Largest raw (decompressed) chunk payload accepted, bytes: 256 MiB. A larger size can only
/// come from a damaged or hostile file, and refusing it bounds what a reader allocates.
inline constexpr uint32 kMaxChunkBytes = 256u << 20;
/// Largest number of frames a replay may hold: 2^24 (77 hours at 60 Hz). Without input bytes
/// (no players' input) a frame takes no room in the file, so only this bound keeps a reader
/// from allocating its per-frame hashes for a count a damaged or hostile file made up.
inline constexpr uint32 kMaxFrames = 1u << 24;
/// Largest number of players, and of input bytes per player per frame.
inline constexpr uint32 kMaxPlayers = 64;
/// Largest input bytes per player per frame.
inline constexpr uint32 kMaxInputBytes = 1024;

/// A chunk type as four ASCII characters, first character in the low byte.
constexpr uint32 ChunkTag(char a, char b, char c, char d) noexcept {
    return static_cast<uint32>(static_cast<uint8>(a)) | (static_cast<uint32>(static_cast<uint8>(b)) << 8) |
           (static_cast<uint32>(static_cast<uint8>(c)) << 16) | (static_cast<uint32>(static_cast<uint8>(d)) << 24);
}

/// The chunk types of format version 1.
enum ChunkType : uint32 {
    e_chunkMeta = ChunkTag('M', 'E', 'T', 'A'),      ///< the game's name and parameters (first chunk)
    e_chunkSeed = ChunkTag('S', 'E', 'E', 'D'),      ///< seed snapshot: world image, user state, hash
    e_chunkInputs = ChunkTag('I', 'N', 'P', 'T'),    ///< a block of consecutive frames' inputs
    e_chunkHashes = ChunkTag('H', 'A', 'S', 'H'),    ///< state hashes at the hash interval
    e_chunkStages = ChunkTag('S', 'T', 'A', 'G'),    ///< per-frame fencepost hashes (optional)
    e_chunkSolve = ChunkTag('S', 'O', 'L', 'V'),     ///< per-frame velocity/position solve hashes (optional;
                                                     ///< added after STAG: older readers skip it)
    e_chunkKeyframe = ChunkTag('K', 'E', 'Y', 'F'),  ///< a snapshot for seeking
    e_chunkEnd = ChunkTag('E', 'N', 'D', '.'),       ///< end record (last chunk)
};

/// Chunk flag bit 0: the stored payload is one zstd frame holding the raw payload.
inline constexpr uint32 kChunkCompressed = 1u;

/// World switches stored in the header (Header::worldFlags).
enum WorldFlag : uint32 {
    e_flagAllowSleep = 1u << 0,
    e_flagWarmStarting = 1u << 1,
    e_flagContinuous = 1u << 2,
    e_flagSubStepping = 1u << 3,
    e_flagAutoClearForces = 1u << 4,
};

/// Fenceposts of one frame stored in a STAG chunk, in this order: after the inputs were
/// applied (before Step), then the four b2StepStage points. A stage the step skipped is 0.
inline constexpr uint32 kStagesPerFrame = 5;
/// Name of stored stage i ("inputs", "collide", "solve", "broadphase", "toi").
LOCKBOX_API const char* StageName(uint32 stage) noexcept;

/// Hashes of one frame's discrete solve stored in a SOLV chunk, in b2IslandPhase order: the
/// velocity phase (every island's body ids and solver velocities after its velocity
/// iterations) and the position phase (ids and solver positions after its position
/// iterations), each one XXH3-64 over all islands in solve order. 0: no solve that frame.
inline constexpr uint32 kSolvePhasesPerFrame = 2;
/// Name of solve phase i ("velocity solve", "position solve").
LOCKBOX_API const char* SolvePhaseName(uint32 phase) noexcept;

/// The fixed header.
struct Header {
    /// kFormatVersion of the writer; a reader refuses other versions.
    uint16 formatVersion = kFormatVersion;
    /// The snapshot's engine field (0.7.0 in every file, whatever the library version; see
    /// b2_snapshotEngineMajor): informative only.
    ///@{
    uint16 engineMajor = 0, engineMinor = 0, enginePatch = 0;
    ///@}
    uint32 determinismVersion = 0;     ///< b2_determinismVersion of the recording engine
    uint16 snapshotFormatVersion = 0;  ///< b2_snapshotFormatVersion of its snapshots
    uint16 tickRate = 60;              ///< frames per second (display and speed reports)
    int32 timeStepRaw = 0;             ///< Q16.16 raw step length passed to b2World::Step, s
    /// Velocity iterations of every recorded b2World::Step.
    uint16 velocityIterations = 8;
    /// Position iterations of every recorded b2World::Step.
    uint16 positionIterations = 3;
    uint32 worldFlags = 0;        ///< WorldFlag bits at the seed
    uint16 playerCount = 1;       ///< 1 .. kMaxPlayers
    uint16 inputBytes = 8;        ///< per player per frame, 0 .. kMaxInputBytes
    uint32 hashInterval = 1;      ///< a hash is stored after every this-many frames (>= 1)
    uint32 keyframeInterval = 0;  ///< a keyframe every this-many frames; 0: none
    uint32 reserved = 0;          ///< written 0; ignored by version-1 readers
};

/// Why a file was refused.
enum class ErrorCode : uint32 {
    e_ok = 0,
    e_io,           ///< the file could not be opened, read or written
    e_truncated,    ///< the bytes end inside the header or a chunk
    e_badMagic,     ///< not a replay file
    e_badVersion,   ///< another (newer or unknown) format version
    e_badEngine,    ///< another determinism or snapshot version: cannot verify bit for bit
    e_badChecksum,  ///< a header or chunk checksum does not match
    e_badChunk,     ///< a chunk is malformed (sizes, order, frames out of sequence)
    e_badSnapshot,  ///< the seed or a keyframe snapshot was refused by b2World::Restore
    e_missing,      ///< a required chunk (META, SEED, END) is missing
    e_usage,        ///< the call does not fit the replay (frame out of range, wrong world)
};

/// Short name of an error code ("truncated", "bad checksum", ...).
LOCKBOX_API const char* ErrorCodeName(ErrorCode code) noexcept;

/// An error with where it happened.
struct LOCKBOX_API Error {
    /// e_ok, or what is wrong.
    ErrorCode code = ErrorCode::e_ok;
    uint64 offset = 0;      ///< byte offset in the file of the header or chunk concerned
    int32 chunkIndex = -1;  ///< 0-based chunk number; -1 for the header
    uint32 chunkType = 0;   ///< the chunk's type tag; 0 for the header
    int32 frame = -1;       ///< the frame concerned; -1 when none
    std::string message;    ///< what is wrong
    /// True when nothing went wrong. (No conversion to bool: lockbox's result types convert to
    /// true on success, and an error type that did so would invite the opposite reading.)
    bool ok() const noexcept { return code == ErrorCode::e_ok; }
    /// One line: "<code> at offset N (chunk i 'TYPE', frame f): message".
    std::string Describe() const;
};

/// The four characters of a chunk tag (non-printable bytes as '?').
LOCKBOX_API std::string ChunkTagName(uint32 tag);

}  // namespace lockbox::replay
