// The testbed's behaviour: scenes, stepping, input and the world views.
#include "Testbed.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include "SceneCatalog.h"
#include "lockbox/scenefile/SceneFile.h"

namespace lockbox::testbed {

namespace {

// Zoom factor per wheel notch and per Z/X key frame.
constexpr double kWheelZoom = 1.15;
constexpr double kKeyZoom = 1.03;
// Arrow keys pan this many pixels per frame.
constexpr double kKeyPan = 8.0;

}  // namespace

Testbed::Testbed(std::string_view name) {
    if (IsSceneFileName(name) && SelectScene(name)) return;
    const auto& catalog = SceneCatalog();
    const int index = CatalogIndex(name);
    sceneIndex_ = index >= 0 ? index : 0;
    if (!catalog.empty()) SelectScene(catalog[static_cast<size_t>(sceneIndex_)].name);
}

bool Testbed::SelectScene(std::string_view name) {
    const int index = CatalogIndex(name);
    if (index < 0 && !IsSceneFileName(name)) return false;
    const StepSettings s = Simulation::DefaultsFor(name, base_);
    if (!primary_.Load(name, s)) return false;
    if (index >= 0) sceneIndex_ = index;
    if (mode_ == ViewMode::replay) CloseReplay();
    dragging_ = false;
    SyncSecondary();
    FitView();
    return true;
}

bool Testbed::OpenSceneFile(const std::string& path) {
    scenefile::SceneResult error;
    // Checked here for its message; SelectScene then opens it again as a scene.
    if (!scenes::SceneFileScene::Open(path, &error)) {
        status_ = path + ": " + error.Describe();
        return false;
    }
    if (!SelectScene(std::string(kSceneFilePrefix) + path)) {
        status_ = "cannot open " + path;
        return false;
    }
    status_ = "opened " + path;
    return true;
}

bool Testbed::SaveWorld(const std::string& path) {
    if (!primary_.Loaded()) return false;
    const scenes::SceneFileScene* file = primary_.SceneFile();
    const scenefile::SceneResult r =
        scenefile::SaveSceneFile(path, primary_.World(), file ? &file->Metadata() : nullptr);
    char frame[48];
    std::snprintf(frame, sizeof frame, " (frame %d)", primary_.Frame());
    status_ = r ? "saved the world to " + path + frame : r.Describe();
    return r.ok();
}

void Testbed::SyncSecondary() {
    if (!sideBySide_ || !primary_.Loaded()) return;
    StepSettings b = primary_.Settings();
    b.velocityIterations = iterationsB_[0];
    b.positionIterations = iterationsB_[1];
    secondary_.Load(primary_.SceneName(), b);
    // Catch up when turned on mid-run, so both views show the same frame.
    while (secondary_.Frame() < primary_.Frame()) secondary_.Step();
}

void Testbed::SetSideBySide(bool on) {
    sideBySide_ = on;
    SyncSecondary();
}

void Testbed::RestartLive() {
    primary_.Restart();
    SyncSecondary();
}

void Testbed::StepScene(int delta) {
    const auto& catalog = SceneCatalog();
    const int n = static_cast<int>(catalog.size());
    if (n == 0) return;
    SelectScene(catalog[static_cast<size_t>(((sceneIndex_ + delta) % n + n) % n)].name);
}

void Testbed::SetWindow(int width, int height, float scale) {
    windowWidth_ = std::max(width, 1);
    windowHeight_ = std::max(height, 1);
    scale_ = scale > 0 ? scale : 1.0f;
}

std::vector<Viewport> Testbed::Views() const {
    const int width = std::max(windowWidth_ - (showPanel_ ? kPanelWidth : 0), 2);
    if (!(sideBySide_ && mode_ == ViewMode::live)) return {Viewport{0, 0, width, windowHeight_}};
    const int half = width / 2;
    return {Viewport{0, 0, half, windowHeight_}, Viewport{half, 0, width - half, windowHeight_}};
}

Simulation* Testbed::ViewSimulation(size_t i) {
    if (mode_ != ViewMode::live) return nullptr;
    Simulation* sim = i == 0 ? &primary_ : &secondary_;
    return sim->Loaded() ? sim : nullptr;
}

b2World* Testbed::ViewWorld(size_t i) {
    if (mode_ == ViewMode::replay) return viewer_.IsOpen() ? &viewer_.World() : nullptr;
    Simulation* sim = ViewSimulation(i);
    return sim ? &sim->World() : nullptr;
}

void Testbed::FitView() {
    if (b2World* world = ViewWorld(0)) FitWorld(camera_, Views()[0], *world);
}

void Testbed::HandleInput() {
    ImGuiIO& io = ImGui::GetIO();
    const std::vector<Viewport> views = Views();
    const double mx = io.MousePos.x, my = io.MousePos.y;

    if (!io.WantCaptureMouse) {
        size_t under = views.size();
        for (size_t i = 0; i < views.size(); ++i)
            if (views[i].Contains(mx, my)) under = i;
        if (under < views.size()) {
            const Viewport& vp = views[under];
            if (io.MouseWheel != 0.0f) camera_.ZoomAt(vp, mx, my, io.MouseWheel > 0 ? 1 / kWheelZoom : kWheelZoom);
            if (ImGui::IsMouseDown(ImGuiMouseButton_Right)) camera_.PanPixels(vp, io.MouseDelta.x, io.MouseDelta.y);
            if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
                if (Simulation* sim = ViewSimulation(under)) {
                    // Display to simulation: the documented rounding helper, nothing else.
                    dragging_ = sim->Grab(RoundDisplayToFixed(camera_.ScreenToWorld(vp, mx, my)));
                    dragView_ = under;
                }
            }
        }
    }
    if (dragging_) {
        Simulation* sim = ViewSimulation(dragView_);
        if (!sim || !ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
            if (sim) sim->Release();
            dragging_ = false;
        } else if (dragView_ < views.size()) {
            sim->DragTo(RoundDisplayToFixed(camera_.ScreenToWorld(views[dragView_], mx, my)));
        }
    }

    if (io.WantCaptureKeyboard) return;
    const Viewport& vp = views[0];
    // Keys are GLFW key codes (Dear ImGui 1.86 indexes its key state by the backend's codes).
    if (ImGui::IsKeyDown(GLFW_KEY_LEFT)) camera_.PanPixels(vp, kKeyPan, 0);
    if (ImGui::IsKeyDown(GLFW_KEY_RIGHT)) camera_.PanPixels(vp, -kKeyPan, 0);
    if (ImGui::IsKeyDown(GLFW_KEY_UP)) camera_.PanPixels(vp, 0, kKeyPan);
    if (ImGui::IsKeyDown(GLFW_KEY_DOWN)) camera_.PanPixels(vp, 0, -kKeyPan);
    const double cx = vp.x + 0.5 * vp.width, cy = vp.y + 0.5 * vp.height;
    if (ImGui::IsKeyDown(GLFW_KEY_Z)) camera_.ZoomAt(vp, cx, cy, 1 / kKeyZoom);
    if (ImGui::IsKeyDown(GLFW_KEY_X)) camera_.ZoomAt(vp, cx, cy, kKeyZoom);
    if (ImGui::IsKeyPressed(GLFW_KEY_HOME, false)) FitView();
    if (ImGui::IsKeyPressed(GLFW_KEY_P, false)) {
        if (mode_ == ViewMode::replay)
            replayPlaying_ = !replayPlaying_;
        else
            paused_ = !paused_;
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_O, true)) {
        paused_ = true;
        replayPlaying_ = false;
        stepOnce_ = true;
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false) && mode_ == ViewMode::live) RestartLive();
    if (ImGui::IsKeyPressed(GLFW_KEY_LEFT_BRACKET, true)) StepScene(-1);
    if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT_BRACKET, true)) StepScene(1);
    if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false)) showPanel_ = !showPanel_;
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) quit_ = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) screenshot_ = true;
}

void Testbed::Advance() {
    const bool single = stepOnce_;
    stepOnce_ = false;
    if (mode_ == ViewMode::replay) {
        if (viewer_.IsOpen() && (replayPlaying_ || single) && !viewer_.StepForward()) replayPlaying_ = false;
        return;
    }
    if (!paused_ || single) StepLive(1);
}

void Testbed::StepLive(int n) {
    for (int i = 0; i < n; ++i) {
        primary_.Step();
        if (sideBySide_) secondary_.Step();
    }
}

bool Testbed::StartRecording(const std::string& path) {
    if (mode_ != ViewMode::live) return false;
    dragging_ = false;
    const bool ok = primary_.StartRecording(path, status_);
    if (path.c_str() != replayPath_) std::snprintf(replayPath_, sizeof replayPath_, "%s", path.c_str());
    SyncSecondary();  // the recording restarted the scene: B restarts with it
    return ok;
}

bool Testbed::StopRecording() { return primary_.StopRecording(status_); }

bool Testbed::OpenReplay(const std::string& path) {
    if (primary_.Recording() || !viewer_.Open(path, status_)) return false;
    if (path.c_str() != replayPath_) std::snprintf(replayPath_, sizeof replayPath_, "%s", path.c_str());
    if (dragging_) primary_.Release();
    dragging_ = false;
    mode_ = ViewMode::replay;
    replayPlaying_ = false;
    checkText_.clear();
    FitView();
    return true;
}

void Testbed::CloseReplay() {
    viewer_.Close();
    mode_ = ViewMode::live;
}

bool Testbed::SeekReplay(int frame) {
    replayPlaying_ = false;
    return mode_ == ViewMode::replay && viewer_.Seek(frame, status_);
}

void Testbed::VerifyReplay() {
    if (mode_ == ViewMode::replay) checkText_ = viewer_.Verify();
}

void Testbed::JumpToDivergence() {
    replayPlaying_ = false;
    if (mode_ == ViewMode::replay) checkText_ = viewer_.BisectAndJump();
}

void Testbed::DrawView(size_t i, const Viewport& vp) {
    camera_.Apply(vp, windowHeight_, scale_);
    // The second view is a shade bluer, so the two accuracy settings are told apart at once.
    if (i == 0)
        glClearColor(0.11f, 0.11f, 0.13f, 1.0f);
    else
        glClearColor(0.10f, 0.12f, 0.17f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    b2World* world = ViewWorld(i);
    if (!world) return;
    uint32 flags = 0;
    if (options_.shapes) flags |= b2Draw::e_shapeBit;
    if (options_.joints) flags |= b2Draw::e_jointBit;
    if (options_.aabbs) flags |= b2Draw::e_aabbBit;
    if (options_.pairs) flags |= b2Draw::e_pairBit;
    if (options_.centersOfMass) flags |= b2Draw::e_centerOfMassBit;
    draw_.SetFlags(flags);
    world->SetDebugDraw(&draw_);
    world->DrawDebugData();
    world->SetDebugDraw(nullptr);
    // b2World does not draw mouse joints (as in 2.2.1): the testbed draws its own.
    if (Simulation* sim = ViewSimulation(i)) {
        if (b2MouseJoint* j = sim->Grabbed()) {
            const b2Vec2 a = j->GetAnchorB(), t = j->GetTarget();
            const float dot = static_cast<float>(4 * camera_.MetresPerPixel(vp));
            const b2Color green(0.0f, 1.0f, 0.0f), grey(0.8f, 0.8f, 0.8f);
            draw_.Point(a.x.ToFloat(), a.y.ToFloat(), dot, green);
            draw_.Point(t.x.ToFloat(), t.y.ToFloat(), dot, green);
            draw_.Line(a.x.ToFloat(), a.y.ToFloat(), t.x.ToFloat(), t.y.ToFloat(), grey);
        }
    }
    draw_.Flush();
}

void Testbed::Render() {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_LIGHTING);
    glDisable(GL_TEXTURE_2D);
    glEnable(GL_SCISSOR_TEST);
    const auto views = Views();
    // The panel strip: cleared once over the whole window first.
    glScissor(0, 0, static_cast<GLsizei>(windowWidth_ * scale_), static_cast<GLsizei>(windowHeight_ * scale_));
    glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    for (size_t i = 0; i < views.size(); ++i) DrawView(i, views[i]);
    glDisable(GL_SCISSOR_TEST);
    glViewport(0, 0, static_cast<GLsizei>(windowWidth_ * scale_), static_cast<GLsizei>(windowHeight_ * scale_));
}

void Testbed::DrawLabels() {
    if (!options_.labels) return;
    ImDrawList* list = ImGui::GetBackgroundDrawList();
    const auto views = Views();
    for (size_t i = 0; i < views.size(); ++i) {
        char text[256];
        if (mode_ == ViewMode::replay) {
            if (!viewer_.IsOpen()) continue;
            std::snprintf(text, sizeof text, "replay %s  frame %d / %d\nhash %016llx %s",
                          viewer_.File().gameName.c_str(), viewer_.Frame(), viewer_.FrameCount(),
                          static_cast<unsigned long long>(viewer_.Hash()),
                          viewer_.MatchesRecording() ? "(matches the recording)" : "(DIFFERS from the recording)");
        } else {
            Simulation* sim = ViewSimulation(i);
            if (!sim) continue;
            const StepSettings& s = sim->Settings();
            std::snprintf(text, sizeof text, "%s  %d Hz  %d/%d iterations  frame %d%s\nhash %016llx",
                          sim->SceneName().c_str(), s.hz, s.velocityIterations, s.positionIterations, sim->Frame(),
                          sim->Recording() ? "  [REC]" : (paused_ ? "  [paused]" : ""),
                          static_cast<unsigned long long>(sim->Hash()));
        }
        list->AddText(ImVec2(static_cast<float>(views[i].x + 8), static_cast<float>(views[i].y + 6)),
                      IM_COL32(230, 230, 230, 255), text);
    }
}

}  // namespace lockbox::testbed
