#pragma once
/// One running scene of the testbed: its world, the step settings from the panel, the mouse
/// joint that drags bodies, the figures shown as text (hash, profile, headroom) and recording
/// to a replay file.
///
/// Every step goes through the WorldGame interface (TestbedGame::Apply, then b2World::Step
/// with dt = round(65536 / hz) raw), whether or not a recorder is attached, so a recorded run
/// is the run on screen, bit for bit.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "TestbedGame.h"
#include "lockbox/dynamics/joints/MouseJoint.h"
#include "lockbox/lockbox.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/scenes/SceneFileScene.h"

namespace lockbox::testbed {

/// Step settings and world switches, as the panel edits them.
struct StepSettings {
    int hz = 60;                 ///< steps per simulated second (dt = round(65536 / hz) raw)
    int velocityIterations = 8;  ///< velocity iterations per step
    int positionIterations = 3;  ///< position iterations per step
    bool sleep = true;           ///< b2World::SetAllowSleeping
    bool warmStarting = true;    ///< b2World::SetWarmStarting
    bool continuous = true;      ///< b2World::SetContinuousPhysics
    bool subStepping = false;    ///< b2World::SetSubStepping
    bool headroom = true;        ///< headroom telemetry after each step (a walk of the world)
};

/// A scene, its world and its controls.
class Simulation {
public:
    Simulation() = default;
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;
    ~Simulation();

    /// Builds scene `name` with `settings`; false (nothing changes) for an unknown name.
    bool Load(std::string_view name, const StepSettings& settings);
    /// The defaults of a scene (its Hz, iterations and sleep flag; the other switches as given,
    /// except for a scene file, whose switches are the file's).
    static StepSettings DefaultsFor(std::string_view name, const StepSettings& base);
    /// The loaded scene when it is a scene file, else nullptr.
    const scenes::SceneFileScene* SceneFile() const noexcept {
        return game_ ? dynamic_cast<const scenes::SceneFileScene*>(&game_->scene()) : nullptr;
    }
    /// Rebuilds the current scene from scratch with the current settings (stops a recording).
    void Restart();
    /// True once a scene is loaded.
    bool Loaded() const noexcept { return game_ != nullptr; }
    /// The loaded scene's name.
    const std::string& SceneName() const noexcept { return name_; }
    /// The scene's world (only when Loaded()).
    b2World& World() noexcept { return game_->world(); }
    /// The settings of the next step (the panel edits them in place).
    StepSettings& Settings() noexcept { return settings_; }
    const StepSettings& Settings() const noexcept { return settings_; }

    /// One frame: the scene's pre-step action, then b2World::Step (recorded when recording).
    void Step();
    /// Frames stepped since the scene was built.
    int32 Frame() const noexcept { return frame_; }
    /// b2World::Hash after the last step (or after building).
    uint64 Hash() const noexcept { return hash_; }

    /// Grabs the dynamic body under world point p with a mouse joint; false when there is
    /// none or while recording (the pointer is not a replay input).
    bool Grab(const b2Vec2& p);
    /// Moves the mouse joint's target.
    void DragTo(const b2Vec2& p);
    /// Destroys the mouse joint, if any.
    void Release();
    /// The live mouse joint, or nullptr.
    b2MouseJoint* Grabbed();

    /// Restarts the scene and records it to `path` from its first frame on; message says what
    /// happened. False when the file cannot be created.
    bool StartRecording(const std::string& path, std::string& message);
    /// Finishes and closes the file.
    bool StopRecording(std::string& message);
    /// True between StartRecording and StopRecording.
    bool Recording() const noexcept { return recorder_ != nullptr; }
    /// Frames in the current recording.
    int32 RecordedFrames() const noexcept;
    /// Where the last recording went.
    const std::string& RecordingPath() const noexcept { return recordingPath_; }

private:
    void ApplySwitches();
    void DropRecorder();

    std::string name_;
    StepSettings settings_;
    std::unique_ptr<TestbedGame> game_;
    int32 frame_ = 0;
    uint64 hash_ = 0;
    b2MouseJoint* mouseJoint_ = nullptr;
    int32 mouseJointId_ = -1;
    std::unique_ptr<replay::FileSink> sink_;
    std::unique_ptr<replay::Recorder> recorder_;
    std::string recordingPath_;
    std::vector<uint8> noInputs_;
};

}  // namespace lockbox::testbed
