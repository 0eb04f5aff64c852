#pragma once
/// @file
/// SyncTestSession: the sync test as a session type. It drives a WorldGame on a
/// lockbox world through core's lockbox::SyncTest (state/SyncTest.h): every frame is run,
/// hashed, then the last `checkDistance` frames are rolled back and re-simulated (in
/// mispredict mode first with wrong inputs, then again with the right ones) and every
/// re-simulated hash must equal the first. It rolls back through rollback frames, as the
/// adapter does in a match (portable images as an option), and a mismatch names the first
/// differing hash category and body. Run it in a game's debug build: a mismatch names
/// state that the game's save misses, before any network is involved.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "lockbox/Export.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/state/SyncTest.h"

namespace lockbox::net {

/// How a sync test session rolls back.
enum class SyncTestRestore : uint8_t {
    /// Rollback frames (b2World::SaveFrame/RestoreFrame), the path WorldGameAdapter takes in a
    /// match: SyncTestResult::frameRestores counts how each restore went.
    e_frames = 0,
    /// Portable images (b2World::Save/Restore), the path of files, peers and late joins;
    /// frameRestores stays zero.
    e_images = 1,
};

/// Settings of a sync test session.
struct SyncTestSessionConfig {
    uint32_t players = 2;        ///< 1 .. kRollbackMaxPlayers
    uint32_t inputBytes = 8;     ///< 1 .. kRollbackMaxInputBytes
    uint32_t checkDistance = 8;  ///< frames re-simulated after each frame, 1 .. kRollbackMaxWindow
    bool mispredict = false;     ///< re-simulate with wrong inputs first
    uint64_t seed = 0x5eed;      ///< wrong-input generator (mispredict mode)
    SyncTestRestore restore = SyncTestRestore::e_frames;  ///< the restore path tested
    WorldStepSettings step;                               ///< how each frame steps the world
};

/// The sync test settings of a session built with RollbackSessionBuilder (players, input
/// bytes and CheckDistance), so one builder describes both the real and the test session.
LOCKBOX_API SyncTestSessionConfig SyncTestConfigFrom(const RollbackConfig& config, WorldStepSettings step,
                                                     bool mispredict);

/// The game's own executor of rollback requests (what it runs in a live match): executes
/// `requests` in order and hands the hash of every SaveState that wants one to `reportHash` at
/// the save, as it would to RollbackSession::ReportHash. False when it cannot go on.
using SyncTestExecutor =
    std::function<bool(std::span<const RollbackRequest> requests, const RollbackHashReport& reportHash)>;

/// Requests a request-driven sync test executed, by kind (SyncTestSession::RequestCounts).
struct SyncTestRequestCounts {
    uint64_t saves = 0;              ///< SaveState
    uint64_t loads = 0;              ///< LoadState: rollbacks, wrong branches included
    uint64_t advances = 0;           ///< AdvanceRequest
    uint64_t predictedAdvances = 0;  ///< advances of a wrong branch (status e_predicted)
};

/// The sync test as a session: runs a WorldGame on a world, rolls back and re-simulates the last
/// checkDistance frames after each frame (Run, or through the requests a live session makes:
/// RunRequests) and reports the first frame whose re-simulated hash differs, which names state
/// the game's save misses (see the file comment).
class LOCKBOX_API SyncTestSession {
public:
    /// `world`, `game` and the source must outlive the session; the world must be in its
    /// starting state (frame 0).
    SyncTestSession(b2World& world, WorldGame& game, SyncTestInputSource inputs, SyncTestSessionConfig config);
    ~SyncTestSession();
    SyncTestSession(const SyncTestSession&) = delete;
    SyncTestSession& operator=(const SyncTestSession&) = delete;

    /// Runs frames [0, frames); stops at the first mismatch (SyncTestResult says where).
    SyncTestResult Run(int32_t frames);

    /// The same check through the requests a live RollbackSession makes, executed by the
    /// game's own executor (its save, load and advance code): per frame Advance{f} +
    /// SaveState{f + 1}, then LoadState{f + 1 - checkDistance} and Advance + SaveState up to
    /// f + 1 again, every hash reported for a re-simulated frame compared with the first one.
    /// In mispredict mode a branch of wrong inputs (seeded bytes, status e_predicted) runs and
    /// is rolled back first, as after a wrong prediction. A mismatch names the first
    /// differing hash category and body (the world is inspected when the hash is reported, so
    /// the executor must work on this session's world), or the user state. The world must be
    /// at frame 0; config.restore does not apply (the executor restores its own way).
    SyncTestResult RunRequests(int32_t frames, const SyncTestExecutor& executor);
    /// RunRequests with a WorldGameAdapter on the session's world and game as the executor:
    /// the match's own save, restore (rollback frames) and step.
    SyncTestResult RunRequests(int32_t frames);
    /// Requests executed by RunRequests so far.
    const SyncTestRequestCounts& RequestCounts() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace lockbox::net
