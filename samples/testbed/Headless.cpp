// Headless rendering into a framebuffer object, PNG output (stb_image_write) and the blank check.
#define GLFW_INCLUDE_GLEXT  // GLFW includes GL/glext.h after GL/gl.h, which it needs first
#include "Headless.h"

#include <imgui.h>
#include <imgui_impl_opengl2.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <cstdint>
#include <cstdio>
#include <unordered_set>
#include <vector>

#include <GLFW/glfw3.h>

#include "SceneCatalog.h"
#include "Testbed.h"

namespace lockbox::testbed {

namespace {

// The framebuffer-object entry points (OpenGL 3.0 / ARB_framebuffer_object), looked up at run
// time: libGL only exports OpenGL 1.x symbols.
struct FramebufferApi {
    PFNGLGENFRAMEBUFFERSPROC genFramebuffers = nullptr;
    PFNGLBINDFRAMEBUFFERPROC bindFramebuffer = nullptr;
    PFNGLDELETEFRAMEBUFFERSPROC deleteFramebuffers = nullptr;
    PFNGLGENRENDERBUFFERSPROC genRenderbuffers = nullptr;
    PFNGLBINDRENDERBUFFERPROC bindRenderbuffer = nullptr;
    PFNGLDELETERENDERBUFFERSPROC deleteRenderbuffers = nullptr;
    PFNGLRENDERBUFFERSTORAGEPROC renderbufferStorage = nullptr;
    PFNGLFRAMEBUFFERRENDERBUFFERPROC framebufferRenderbuffer = nullptr;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC checkFramebufferStatus = nullptr;

    bool Load() {
        auto get = [](const char* name) { return glfwGetProcAddress(name); };
        genFramebuffers = reinterpret_cast<PFNGLGENFRAMEBUFFERSPROC>(get("glGenFramebuffers"));
        bindFramebuffer = reinterpret_cast<PFNGLBINDFRAMEBUFFERPROC>(get("glBindFramebuffer"));
        deleteFramebuffers = reinterpret_cast<PFNGLDELETEFRAMEBUFFERSPROC>(get("glDeleteFramebuffers"));
        genRenderbuffers = reinterpret_cast<PFNGLGENRENDERBUFFERSPROC>(get("glGenRenderbuffers"));
        bindRenderbuffer = reinterpret_cast<PFNGLBINDRENDERBUFFERPROC>(get("glBindRenderbuffer"));
        deleteRenderbuffers = reinterpret_cast<PFNGLDELETERENDERBUFFERSPROC>(get("glDeleteRenderbuffers"));
        renderbufferStorage = reinterpret_cast<PFNGLRENDERBUFFERSTORAGEPROC>(get("glRenderbufferStorage"));
        framebufferRenderbuffer = reinterpret_cast<PFNGLFRAMEBUFFERRENDERBUFFERPROC>(get("glFramebufferRenderbuffer"));
        checkFramebufferStatus = reinterpret_cast<PFNGLCHECKFRAMEBUFFERSTATUSPROC>(get("glCheckFramebufferStatus"));
        return genFramebuffers && bindFramebuffer && deleteFramebuffers && genRenderbuffers && bindRenderbuffer &&
               deleteRenderbuffers && renderbufferStorage && framebufferRenderbuffer && checkFramebufferStatus;
    }
};

// An RGBA8 colour renderbuffer attached to a framebuffer object, bound while alive.
class Offscreen {
public:
    Offscreen(FramebufferApi& api, int width, int height) : api_(api) {
        api_.genFramebuffers(1, &fbo_);
        api_.bindFramebuffer(GL_FRAMEBUFFER, fbo_);
        api_.genRenderbuffers(1, &colour_);
        api_.bindRenderbuffer(GL_RENDERBUFFER, colour_);
        api_.renderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        api_.framebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
        ok_ = api_.checkFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
    ~Offscreen() {
        api_.bindFramebuffer(GL_FRAMEBUFFER, 0);
        api_.deleteRenderbuffers(1, &colour_);
        api_.deleteFramebuffers(1, &fbo_);
    }
    Offscreen(const Offscreen&) = delete;
    Offscreen& operator=(const Offscreen&) = delete;
    bool ok() const noexcept { return ok_; }

private:
    FramebufferApi& api_;
    GLuint fbo_ = 0, colour_ = 0;
    bool ok_ = false;
};

// One ImGui + world frame of the testbed into the bound framebuffer.
void RenderFrame(Testbed& testbed, int width, int height) {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
    io.DeltaTime = 1.0f / 60.0f;
    ImGui_ImplOpenGL2_NewFrame();
    ImGui::NewFrame();
    testbed.DrawPanels();
    ImGui::Render();
    testbed.Render();
    ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
}

// Opens the replay and applies the replay options; returns an exit code.
int ShowReplay(Testbed& testbed, const HeadlessOptions& options) {
    if (!testbed.OpenReplay(options.replay)) return 1;
    FaultInjector& fault = testbed.Fault();
    fault.enabled = options.injectFrame >= 0;
    fault.frame = options.injectFrame;
    fault.stage = options.injectStage;
    if (options.replayFrame >= 0 && !testbed.SeekReplay(options.replayFrame)) return 1;
    if (options.verify) testbed.VerifyReplay();
    if (options.bisect) testbed.JumpToDivergence();
    return 0;
}

}  // namespace

int RunHeadless(const HeadlessOptions& options) {
    if (options.replay.empty() && CatalogIndex(options.scene) < 0 && !IsSceneFileName(options.scene)) {
        std::fprintf(stderr, "unknown scene '%s' (--list shows them)\n", options.scene.c_str());
        return 2;
    }
    if (!glfwInit()) {
        std::fprintf(stderr, "cannot initialise GLFW (no display? run under xvfb-run -a)\n");
        return 2;
    }
    // A hidden window only provides the GL context; the frame goes to a framebuffer object.
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(64, 64, "lockbox testbed (headless)", nullptr, nullptr);
    if (!window) {
        std::fprintf(stderr, "cannot create an OpenGL context\n");
        glfwTerminate();
        return 2;
    }
    glfwMakeContextCurrent(window);
    int code = 0;
    {
        FramebufferApi api;
        if (!api.Load()) {
            std::fprintf(stderr, "OpenGL framebuffer objects are not available\n");
            code = 2;
        } else {
            Offscreen target(api, options.width, options.height);
            if (!target.ok()) {
                std::fprintf(stderr, "cannot make a %dx%d framebuffer\n", options.width, options.height);
                code = 2;
            } else {
                ImGui::CreateContext();
                ImGui::GetIO().IniFilename = nullptr;
                ImGui::StyleColorsDark();
                ImGui_ImplOpenGL2_Init();
                {
                    Testbed testbed(options.scene);
                    testbed.SetWindow(options.width, options.height, 1.0f);
                    testbed.ShowPanel(options.panel);
                    testbed.SetSideBySide(options.sideBySide);
                    if (!options.record.empty() && !testbed.StartRecording(options.record)) code = 1;
                    testbed.StepLive(options.steps);
                    if (!options.record.empty() && !testbed.StopRecording()) code = 1;
                    if (!options.replay.empty()) code = ShowReplay(testbed, options);
                    if (!testbed.Status().empty()) std::printf("%s\n", testbed.Status().c_str());
                    if (!testbed.CheckText().empty()) std::printf("%s\n", testbed.CheckText().c_str());
                    testbed.FitView();
                    // ImGui lays new windows out over a frame or two before it draws them all.
                    for (int i = 0; i < 3; ++i) RenderFrame(testbed, options.width, options.height);
                    glFinish();
                    if (code != 0) {
                        // the message is printed above
                    } else if (!WriteFramebufferPng(options.output, options.width, options.height)) {
                        std::fprintf(stderr, "cannot write %s\n", options.output.c_str());
                        code = 1;
                    } else {
                        std::printf("wrote %s\n", options.output.c_str());
                    }
                }
                ImGui_ImplOpenGL2_Shutdown();
                ImGui::DestroyContext();
            }
        }
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return code;
}

bool WriteFramebufferPng(const std::string& path, int width, int height) {
    std::vector<unsigned char> pixels(static_cast<size_t>(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    // GL rows run bottom-up, PNG rows top-down; the picture is opaque, so drop alpha.
    std::vector<unsigned char> rgb(static_cast<size_t>(width) * height * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(static_cast<size_t>(height - 1 - y) * width + x) * 3 + c] =
                    pixels[(static_cast<size_t>(y) * width + x) * 4 + c];
    return stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3) != 0;
}

int CheckImage(const std::string& path) {
    int width = 0, height = 0, channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 4);
    if (!data) {
        std::fprintf(stderr, "%s: cannot read the image\n", path.c_str());
        return 2;
    }
    std::unordered_set<uint32_t> colours;
    const size_t n = static_cast<size_t>(width) * height;
    for (size_t i = 0; i < n && colours.size() < 1000; ++i) {
        const unsigned char* p = data + 4 * i;
        colours.insert(uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24);
    }
    stbi_image_free(data);
    std::printf("%s: %dx%d, %s%zu distinct colours\n", path.c_str(), width, height, colours.size() >= 1000 ? ">= " : "",
                colours.size());
    return colours.size() > 1 ? 0 : 1;
}

}  // namespace lockbox::testbed
