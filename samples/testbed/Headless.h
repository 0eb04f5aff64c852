#pragma once
/// The testbed without a window: run a scene N steps, render one frame into an offscreen
/// framebuffer and write it as a PNG (docs pictures, the CI smoke test); and the check that a
/// PNG is not blank.

#include <string>

namespace lockbox::testbed {

/// What the headless run renders.
struct HeadlessOptions {
    std::string scene;   ///< catalog name
    int steps = 0;       ///< steps before the frame
    std::string output;  ///< PNG path
    int width = 1280;    ///< image size, px
    int height = 720;
    bool panel = true;        ///< draw the side panel as in the window
    bool sideBySide = false;  ///< two views at accuracy A and B
    std::string record;       ///< when set, the steps are recorded to this replay file
    std::string replay;       ///< when set, the frame shows this replay instead of the scene
    int replayFrame = -1;     ///< frame of the replay to show (-1: the seed)
    int injectFrame = -1;     ///< fault injection at this frame (-1: none) ...
    int injectStage = 2;      ///< ... and this stage
    bool verify = false;      ///< verify the replay (verdict printed and shown)
    bool bisect = false;      ///< show the state before the replay's first divergent frame
};

/// Renders the frame and writes the PNG (needs an X display for GLFW's hidden window; Xvfb
/// will do). Returns a process exit code: 0 on success.
int RunHeadless(const HeadlessOptions& options);

/// Writes the bound framebuffer's pixels (width x height, from the origin) as an RGB PNG.
bool WriteFramebufferPng(const std::string& path, int width, int height);

/// Reads a PNG and counts its distinct colours; 0 when there are at least two (the image is
/// not blank), 1 when it is blank, 2 when it cannot be read.
int CheckImage(const std::string& path);

}  // namespace lockbox::testbed
