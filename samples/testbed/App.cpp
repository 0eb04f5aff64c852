// The interactive loop: GLFW events, ImGui frame, testbed input/step/panels, GL drawing.
#include "App.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl2.h>

#include <cstdio>

#include <GLFW/glfw3.h>

#include "Headless.h"
#include "Testbed.h"

namespace lockbox::testbed {

namespace {

void OnGlfwError(int code, const char* description) { std::fprintf(stderr, "GLFW error %d: %s\n", code, description); }

// Window size and framebuffer scale into the testbed (they change when the window is resized).
void UpdateWindow(GLFWwindow* window, Testbed& testbed) {
    int w = 0, h = 0, fw = 0, fh = 0;
    glfwGetWindowSize(window, &w, &h);
    glfwGetFramebufferSize(window, &fw, &fh);
    testbed.SetWindow(w, h, w > 0 ? static_cast<float>(fw) / static_cast<float>(w) : 1.0f);
}

}  // namespace

int RunApp(const AppOptions& options) {
    glfwSetErrorCallback(OnGlfwError);
    if (!glfwInit()) {
        std::fprintf(stderr, "cannot initialise GLFW (is there a display?)\n");
        return 2;
    }
    GLFWwindow* window = glfwCreateWindow(1400, 860, "lockbox testbed", nullptr, nullptr);
    if (!window) {
        glfwTerminate();
        return 2;
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);  // one step per displayed frame, paced by the display

    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed: nothing to save
    ImGui::StyleColorsDark();
    // install_callbacks: ImGui's GLFW backend feeds mouse, wheel and keys to io, which the
    // testbed reads (Testbed::HandleInput).
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL2_Init();
    {
        Testbed testbed(options.scene);
        UpdateWindow(window, testbed);
        testbed.SetSideBySide(options.sideBySide);
        testbed.StepLive(options.steps);
        testbed.FitView();
        if (options.paused) testbed.SetPaused(true);
        int shot = 0;
        while (!glfwWindowShouldClose(window) && !testbed.QuitRequested()) {
            glfwPollEvents();
            UpdateWindow(window, testbed);
            ImGui_ImplOpenGL2_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            testbed.HandleInput();
            testbed.Advance();
            testbed.DrawPanels();
            ImGui::Render();
            testbed.Render();
            ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
            if (testbed.TakeScreenshotRequest()) {
                // F12: the back buffer as drawn, numbered so earlier shots stay.
                char path[64];
                std::snprintf(path, sizeof path, "testbed_%03d.png", shot++);
                int fw = 0, fh = 0;
                glfwGetFramebufferSize(window, &fw, &fh);
                glReadBuffer(GL_BACK);
                std::printf("%s %s\n", WriteFramebufferPng(path, fw, fh) ? "wrote" : "cannot write", path);
                std::fflush(stdout);
            }
            glfwSwapBuffers(window);
        }
    }
    ImGui_ImplOpenGL2_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
}

}  // namespace lockbox::testbed
