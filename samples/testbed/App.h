#pragma once
/// The interactive testbed: a GLFW window with an OpenGL 2 context and Dear ImGui.

#include <string>

namespace lockbox::testbed {

/// Window options.
struct AppOptions {
    std::string scene;        ///< first scene (empty: the first of the list)
    int steps = 0;            ///< steps to run before the first frame
    bool sideBySide = false;  ///< start with two views
    bool paused = false;      ///< start paused
};

/// Runs the window until it is closed (or Esc); returns a process exit code.
int RunApp(const AppOptions& options);

}  // namespace lockbox::testbed
