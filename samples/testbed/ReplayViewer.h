#pragma once
/// The replay viewer: loads a replay file, plays and scrubs it (a seek through the nearest
/// keyframe), checks it (replay::Player::Verify) and jumps to the first divergent frame of a
/// failing replay (replay::Bisect).
///
/// A fault can be injected to see what a failing replay looks like: at one frame and stage the
/// first dynamic body's x velocity is nudged by one raw unit (1/65536 m/s) before the stage is
/// hashed, in the viewer's player and in the checks, as `lockbox_replay bisect --inject` does.

#include <memory>
#include <string>

#include "TestbedGame.h"
#include "lockbox/replay/Bisect.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"

namespace lockbox::testbed {

/// Nudges the first dynamic body at one fencepost (a stand-in for a non-deterministic bug).
class FaultInjector : public replay::StageHook {
public:
    bool enabled = false;  ///< off: no effect
    int32 frame = 30;      ///< frame to disturb
    int32 stage = 2;       ///< fencepost (replay::StageName: 0 inputs .. 4 toi)
    /// Nudges the first dynamic body when (atFrame, atStage) is the chosen fencepost.
    void OnStage(int32 atFrame, uint32 atStage, b2World& world) override;
};

/// One loaded replay and its player.
class ReplayViewer {
public:
    /// Loads and parses a file and builds its game; message says what happened.
    bool Open(const std::string& path, std::string& message);
    /// Forgets the file.
    void Close();
    /// True while a replay is loaded.
    bool IsOpen() const noexcept { return player_ != nullptr; }
    /// The loaded file's path and contents.
    const std::string& Path() const noexcept { return path_; }
    const replay::ReplayFile& File() const noexcept { return file_; }
    /// The world being shown.
    b2World& World() noexcept { return *game_.world; }
    /// Frames played since the seed.
    int32 Frame() const noexcept { return player_->Frame(); }
    /// Frames in the replay.
    int32 FrameCount() const noexcept { return file_.frameCount; }
    /// The hash of the shown state, and whether it matches the recording there (true when the
    /// file stores no hash for this frame).
    uint64 Hash() const noexcept { return hash_; }
    bool MatchesRecording() const noexcept;

    /// Brings the shown world to the state after `frame` frames.
    bool Seek(int32 frame, std::string& message);
    /// Plays one frame; false at the end.
    bool StepForward();

    /// Plays the whole file from the seed in a separate world (the shown one stays) and
    /// returns the verdict in one line.
    std::string Verify();
    /// Bisects in a separate world; when the replay diverges, shows the state just before the
    /// divergent frame (step once to see it go wrong). Returns the description.
    std::string BisectAndJump();

    /// The fault injection settings (applied to the shown player and to the checks).
    FaultInjector& Fault() noexcept { return fault_; }

private:
    // A second player over a fresh game, for Verify and Bisect.
    struct Checker {
        ReplayGame game;
        std::unique_ptr<replay::Player> player;
    };
    bool MakeChecker(Checker& out);
    void Refresh();

    std::string path_;
    replay::ReplayFile file_;
    ReplayGame game_;
    std::unique_ptr<replay::Player> player_;
    FaultInjector fault_;
    uint64 hash_ = 0;
};

}  // namespace lockbox::testbed
