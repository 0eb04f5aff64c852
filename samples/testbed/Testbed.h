#pragma once
/// The testbed itself, independent of how it is shown: the scene list, the running
/// simulation(s), the replay viewer, the camera and the draw options; input handling, stepping,
/// drawing of the world views and the ImGui panels (Panels.cpp).
///
/// The interactive program (App.cpp) drives it from a GLFW window; the headless mode
/// (Headless.cpp) steps it N times and renders one frame into an offscreen framebuffer. Both
/// call, per displayed frame: ImGui NewFrame, HandleInput, Advance, DrawPanels, then Render
/// and the ImGui draw data.

#include <string>
#include <string_view>
#include <vector>

#include "Camera.h"
#include "GlDraw.h"
#include "ReplayViewer.h"
#include "Simulation.h"

namespace lockbox::testbed {

/// Debug-draw switches (b2Draw flags) and overlays.
struct DrawOptions {
    bool shapes = true;
    bool joints = true;
    bool aabbs = false;
    bool pairs = false;
    bool centersOfMass = false;
    bool labels = true;  ///< scene, settings and hash over each view
};

/// What the views show.
enum class ViewMode { live, replay };

/// The testbed state and behaviour.
class Testbed {
public:
    /// Starts with scene `name` (the first catalog scene when unknown or empty).
    explicit Testbed(std::string_view name);

    /// Switches to a catalog scene with its default settings (keeps the world switches), or to a
    /// scene file ("file:PATH", with the file's switches).
    bool SelectScene(std::string_view name);
    /// Opens a b2dJson scene file; a file that does not load leaves the scene as it was and
    /// puts the error in Status().
    bool OpenSceneFile(const std::string& path);
    /// Saves the live world (with the scene file's names, properties and images, when it came
    /// from one) as a b2dJson file; the outcome goes to Status().
    bool SaveWorld(const std::string& path);
    /// Mouse and keyboard through ImGui's io (call after ImGui::NewFrame); ignores input that
    /// ImGui wants (a click on a panel).
    void HandleInput();
    /// Steps whatever runs (live simulations or the replay) once, unless paused.
    void Advance();
    /// Steps the live simulation(s) n times regardless of pause (headless mode).
    void StepLive(int n);
    /// Fits the camera to the shown world.
    void FitView();
    /// Clears the window and draws the world view(s) (the GL context is current).
    void Render();
    /// Builds the ImGui panels and view labels for this frame.
    void DrawPanels();

    /// Window size in window pixels and framebuffer pixels per window pixel.
    void SetWindow(int width, int height, float scale);
    /// Shows or hides the side panel.
    void ShowPanel(bool show) noexcept { showPanel_ = show; }
    /// Turns side-by-side mode on or off.
    void SetSideBySide(bool on);
    /// Pauses or resumes the live simulation.
    void SetPaused(bool paused) noexcept { paused_ = paused; }
    /// True once after the user asked for a screenshot (F12).
    bool TakeScreenshotRequest() noexcept {
        const bool r = screenshot_;
        screenshot_ = false;
        return r;
    }
    /// True when the user asked to quit (Esc).
    bool QuitRequested() const noexcept { return quit_; }
    /// The main simulation.
    Simulation& Primary() noexcept { return primary_; }

    // Replays (the Replay panel's buttons; the headless mode calls them too).
    /// Restarts the scene and records it to `path` until StopRecording.
    bool StartRecording(const std::string& path);
    /// Finishes the recording and closes its file.
    bool StopRecording();
    /// Opens a replay file; the views show it until CloseReplay.
    bool OpenReplay(const std::string& path);
    /// Forgets the replay; the views show the live scene again.
    void CloseReplay();
    /// Shows the replay's state after `frame` frames.
    bool SeekReplay(int frame);
    /// Verifies the open replay; the verdict goes to CheckText().
    void VerifyReplay();
    /// Bisects the open replay and shows the state before its first divergent frame.
    void JumpToDivergence();
    /// Fault injection for the replay checks.
    FaultInjector& Fault() noexcept { return viewer_.Fault(); }
    /// The last status line (recording, opening, errors) and the last check's verdict.
    const std::string& Status() const noexcept { return status_; }
    const std::string& CheckText() const noexcept { return checkText_; }

private:
    // Width of the side panel, window pixels: the panel (Panels.cpp) and the views left of it.
    static constexpr int kPanelWidth = 360;

    // Viewports of the world views: one, or two side by side, left of the panel.
    std::vector<Viewport> Views() const;
    // The world shown in view i (nullptr: nothing loaded).
    b2World* ViewWorld(size_t i);
    Simulation* ViewSimulation(size_t i);
    void DrawView(size_t i, const Viewport& vp);
    void DrawLabels();
    void RestartLive();
    void SyncSecondary();
    void StepScene(int delta);

    // Panels.cpp
    void ScenePanel();
    void SceneFilePanel();
    void ControlPanel();
    void DrawPanel();
    void StatsPanel();
    void ReplayPanel();
    void SideBySidePanel();
    static void SettingsEditor(StepSettings& s, bool locked, const char* id);
    static void WorldStats(b2World& world, uint64 hash, bool telemetry);

    Simulation primary_;
    Simulation secondary_;  ///< the same scene at accuracy B (side by side)
    ReplayViewer viewer_;
    ViewMode mode_ = ViewMode::live;
    Camera camera_;
    GlDraw draw_;
    DrawOptions options_;
    int sceneIndex_ = 0;
    StepSettings base_;  ///< the switches kept from scene to scene
    int iterationsB_[2] = {2, 1};
    bool sideBySide_ = false;
    bool paused_ = false;
    bool stepOnce_ = false;
    bool replayPlaying_ = false;
    bool showPanel_ = true;
    bool quit_ = false;
    bool screenshot_ = false;
    int windowWidth_ = 1280, windowHeight_ = 720;
    float scale_ = 1.0f;
    bool dragging_ = false;
    size_t dragView_ = 0;
    char replayPath_[512] = "testbed.lbr";
    char sceneFilePath_[512] = "scenes/files/handmade/joints.json";
    char savePath_[512] = "testbed_world.json";
    std::vector<std::string> folderFiles_;  ///< .json files beside sceneFilePath_ (the picker's list)
    std::string listedFolder_;              ///< the folder folderFiles_ lists
    std::string status_;                    ///< last message (recording, opening, errors)
    std::string checkText_;                 ///< last Verify / Bisect result
};

}  // namespace lockbox::testbed
