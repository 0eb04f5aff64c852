#pragma once
/// @file
/// Recording a replay: the Recorder owns the frame loop of a world and a game. Each
/// Advance applies the frame's inputs through the game, steps the world with the recorded
/// settings, hashes the result and appends it; blocks of frames are written as compressed
/// chunks to a sink (memory or file) as they fill, so a crash loses at most one block.

#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/replay/Format.h"
#include "lockbox/replay/Game.h"
#include "lockbox/replay/ReplayFile.h"

namespace lockbox::replay {

/// Where the bytes of a replay go.
class LOCKBOX_API Sink {
public:
    virtual ~Sink() = default;
    /// Appends bytes; false on failure (the recorder then reports e_io).
    virtual bool Write(std::span<const uint8> bytes) = 0;
};

/// A replay kept in memory.
class LOCKBOX_API MemorySink : public Sink {
public:
    bool Write(std::span<const uint8> bytes) override {
        m_bytes.insert(m_bytes.end(), bytes.begin(), bytes.end());
        return true;
    }
    /// The replay bytes written so far.
    ///@{
    const std::vector<uint8>& bytes() const noexcept { return m_bytes; }
    std::vector<uint8>& bytes() noexcept { return m_bytes; }
    ///@}

private:
    std::vector<uint8> m_bytes;
};

/// A replay streamed to a file (created or truncated).
class LOCKBOX_API FileSink : public Sink {
public:
    /// Creates or truncates the file at `path`; ok() tells whether that worked (Write then fails
    /// otherwise).
    explicit FileSink(const std::string& path);
    ~FileSink() override;
    FileSink(const FileSink&) = delete;
    FileSink& operator=(const FileSink&) = delete;
    /// False when the file could not be opened.
    bool ok() const noexcept { return m_file != nullptr; }
    bool Write(std::span<const uint8> bytes) override;
    /// Flushes and closes; false on a write error.
    bool Close();

private:
    std::FILE* m_file = nullptr;
};

/// Recording settings.
struct RecorderConfig {
    std::string gameName;           ///< stored in META; tells a player what to build
    std::vector<uint8> gameParams;  ///< stored in META, opaque
    uint16 tickRate = 60;           ///< frames per second; the step is round(65536 / tickRate) raw
    /// Velocity iterations of every step (the same value the replay player uses).
    uint16 velocityIterations = 8;
    /// Position iterations of every step.
    uint16 positionIterations = 3;
    uint16 playerCount = 1;         ///< 1 .. 64
    uint16 inputBytes = 8;          ///< per player per frame, 0 .. 1024
    uint32 hashInterval = 1;        ///< store a hash after every this-many frames (>= 1)
    uint32 keyframeInterval = 600;  ///< a keyframe every this-many frames; 0: none
    bool stageHashes = false;       ///< store the fencepost hashes of every frame (for bisect)
    uint32 blockFrames = 60;        ///< frames per INPT/HASH/STAG chunk (>= 1)
    int compressionLevel = 3;       ///< zstd level; 0 stores chunks raw
};

/// Records frames of a world driven by a game.
class LOCKBOX_API Recorder {
public:
    /// The world and game must outlive the recorder. Nothing is written before Begin.
    Recorder(b2World& world, Game& game, Sink& sink, RecorderConfig config);
    ~Recorder();
    Recorder(const Recorder&) = delete;
    Recorder& operator=(const Recorder&) = delete;

    /// Writes the header, META and the seed snapshot (the world's current state).
    Error Begin();
    /// One frame: Apply(inputs) then Step. `inputs` must hold playerCount * inputBytes bytes
    /// (shorter is zero-padded, longer is cut). Returns the state hash after the frame when it
    /// is stored, else 0.
    uint64 Advance(std::span<const uint8> inputs);
    /// One frame that a session has already simulated and confirmed (rollback netcode: the
    /// world may already be ahead). `hashAfter` must be b2World::Hash of the state after the
    /// frame; it is stored when the hash interval asks for it. When a keyframe is due,
    /// `worldAtFrame` (the state after the frame, e.g. a confirmed-state copy) is saved with the
    /// game's user state; nullptr skips that keyframe. Stage hashes cannot be recorded this way.
    void AppendConfirmed(std::span<const uint8> inputs, uint64 hashAfter, const b2World* worldAtFrame);
    /// True when the frame appended next is followed by a keyframe (the keyframe interval).
    bool KeyframeDue() const noexcept;
    /// One final frame of a match simulated elsewhere, where neither the recorder's world nor
    /// its game is at that frame (a rollback session runs ahead on predictions): nothing of
    /// them is read. `hashAfter` is b2World::Hash of the state after the frame, needed when the
    /// hash interval stores it (else ignored). When KeyframeDue(), `stateAfter` is that state:
    /// its world image (b2World::Save), hash and the game's user state then (its frame field is
    /// ignored); nullptr skips the keyframe. Finish with Finish(finalHash).
    void AppendFinal(std::span<const uint8> inputs, uint64 hashAfter, const Keyframe* stateAfter);
    /// Writes the pending block and the END record. Further calls do nothing.
    Error Finish();
    /// The same, with `finalHash` as the END record's hash (b2World::Hash after the last frame),
    /// for frames appended with AppendFinal.
    Error Finish(uint64 finalHash);
    /// The settings (after the constructor's clamping).
    const RecorderConfig& Config() const noexcept { return m_config; }
    /// True once Begin has run.
    bool Begun() const noexcept { return m_begun; }
    /// Frames recorded so far.
    int32 Frames() const noexcept { return m_frames; }
    /// The first write error (e_ok while all writes succeeded).
    const Error& WriteError() const noexcept { return m_writeError; }

private:
    void Flush();
    std::span<const uint8> PushInputs(std::span<const uint8> inputs);
    void Record(uint64 hash, const b2World* keyframeWorld, const Keyframe* keyframeState);
    void EmitKeyframe(uint64 hash, std::span<const uint8> image, std::span<const uint8> user);
    void Emit(uint32 type, std::span<const uint8> payload);
    void EmitFrameHashes(uint32 type, int32 count, uint32 per, const std::vector<uint64>& block);

    b2World& m_world;
    Game& m_game;
    Sink& m_sink;
    RecorderConfig m_config;
    Header m_header;
    bool m_begun = false, m_finished = false;
    int32 m_frames = 0;
    int32 m_blockStart = 0;  ///< first frame of the pending block
    std::vector<uint8> m_inputBlock;
    std::vector<uint64> m_hashBlock;
    int32 m_hashBlockStart = -1;  ///< frame of the first pending hash
    std::vector<uint64> m_stageBlock;
    std::vector<uint64> m_solveBlock;
    std::vector<uint8> m_scratch, m_chunk, m_user;
    Error m_writeError;
};

}  // namespace lockbox::replay
