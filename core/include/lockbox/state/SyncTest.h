#pragma once
/// @file
/// lockbox::SyncTest: the rollback self-check of GGRS-style sessions, for any game built on a
/// b2World. Every frame is simulated once and hashed; then the world is restored k frames back
/// and the same k frames are simulated again, and every re-simulated hash must equal the first
/// one. A mismatch means some state that influences a step is missing from the snapshot, or
/// something outside the world changed the result.
///
/// The mispredict mode first re-simulates the k frames with wrong inputs (random impulses,
/// bodies created and destroyed, joints created, chosen by a seeded generator), then restores
/// again and re-simulates with the right ones. Every other branch only spawns (bodies created,
/// joints among them, some of those bodies destroyed again), the case rollback frames undo
/// without their structure image. State that leaks out of a discarded branch (contact caches, pair buffers, id reuse,
/// free-list order) shows up as a mismatch.

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/state/WorldGame.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox {

/// Fills frame `frame`'s inputs (SyncTestConfig::inputBytes bytes, every player's). The sync
/// test asks once per frame and keeps the answer for every re-simulation, so a source need not
/// be a pure function of the frame.
using SyncTestInputSource = std::function<void(int32 frame, std::span<uint8> out)>;

/// Sync test settings.
struct SyncTestConfig {
    int32 checkDistance = 8;  ///< k: frames re-simulated after each rollback (>= 1)
    /// Roll back after every `stride`-th frame (1: after every frame, as GGRS does). A stride
    /// equal to checkDistance still re-simulates and checks every frame, once, at a fraction
    /// of the cost: the choice for very large worlds.
    int32 stride = 1;
    bool mispredict = false;  ///< re-simulate with wrong inputs first, then roll back again
    uint64 seed = 0x5eedULL;  ///< wrong-input generator seed (mispredict mode)
    /// Roll back through rollback frames (b2World::SaveFrame/RestoreFrame) instead of portable
    /// images (Save/Restore). The images are still saved: they give each frame's hash and the
    /// first run's state for a mismatch report.
    bool frames = false;
    /// Bytes of one frame's inputs, every player's (0: the game gets an empty span and the
    /// input source is never called).
    uint32 inputBytes = 0;
    WorldStepSettings step;  ///< how every frame steps the world after WorldGame::Apply
};

/// How a sync test's RestoreFrame calls went (frames mode), by the path each took.
struct SyncTestFrameRestores {
    uint64 sameStructure = 0;      ///< the world's structure was the frame's: the frame's arrays only
    uint64 undoneCreations = 0;    ///< bodies and joints created since the frame were destroyed first
    uint64 restoredStructure = 0;  ///< the frame's structure image was restored first
};

/// What a sync test found.
struct SyncTestResult {
    /// True when every re-simulated frame hashed like the first run.
    bool ok = true;
    int32 framesSimulated = 0;    ///< frames advanced for the first time
    int32 rollbacks = 0;          ///< restores followed by a checked re-simulation
    int32 framesResimulated = 0;  ///< checked re-simulated frames
    int32 firstBadFrame = -1;     ///< the state after this many frames differs (-1: none)
    uint64 expected = 0;          ///< first-run hash at firstBadFrame
    uint64 actual = 0;            ///< re-simulated hash at firstBadFrame
    b2HashMismatch where;         ///< first differing category and body
    std::string message;          ///< a one-line account of the failure; empty when ok
    /// In frames mode: how the run's RestoreFrame calls went (same structure, spawns undone,
    /// structure image restored).
    SyncTestFrameRestores frameRestores;
};

/// Runs a game through the sync test. The world must be in its initial state and is left at
/// the last frame (after the final re-simulation).
class LOCKBOX_API SyncTest {
public:
    /// A sync test of `game` on `world`, fed by `inputs` (may be empty: every frame's inputs
    /// are then zero bytes); the world and the game must outlive it. Each frame is
    /// AdvanceWorldFrame with the frame's inputs and `config.step`.
    SyncTest(b2World& world, WorldGame& game, SyncTestInputSource inputs = {}, SyncTestConfig config = {});
    /// Simulates frames [0, frames) with a rollback check after every frame from k on; stops
    /// at the first mismatch.
    SyncTestResult Run(int32 frames);

private:
    SyncTestResult RunFrames(int32 frames);
    uint64 StateHash();
    /// Saves the frame into the ring and returns its state hash (read from the image).
    uint64 SaveFrame(int32 frame);
    bool LoadFrame(int32 frame, SyncTestResult& result);
    bool CheckFrame(int32 frame, SyncTestResult& result);
    /// Wrong inputs for one frame of a mispredicted branch; `spawnOnly` leaves older bodies and
    /// joints alone (bodies are created, joined and destroyed among `spawned`, the ids of the
    /// branch's own bodies: the game may destroy some of them meanwhile).
    void WrongInputs(int32 frame, bool spawnOnly, std::vector<int32>& spawned);

    /// Frame `frame`'s inputs, asked of the source the first time and kept after.
    std::span<const uint8> InputsFor(int32 frame);
    void Advance(int32 frame);

    b2World& m_world;
    WorldGame& m_game;
    SyncTestInputSource m_source;
    SyncTestConfig m_config;
    std::vector<std::vector<uint8>> m_images;  ///< ring of k + 1 world images, by frame
    std::vector<b2WorldFrame> m_frames;        ///< same ring, in frames mode
    std::vector<std::vector<uint8>> m_user;    ///< the game's state, same ring
    std::vector<uint64> m_hashes;              ///< first-run hash after each frame
    std::vector<std::vector<uint8>> m_inputs;  ///< every frame's inputs asked so far, by frame
    std::vector<uint8> m_scratch;
};

}  // namespace lockbox
