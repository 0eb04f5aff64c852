// The testbed's ImGui panels: scenes, controls, draw options, text, replays, side by side.
#include <imgui.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "SceneCatalog.h"
#include "Testbed.h"
#include "lockbox/replay/Format.h"
#include "lockbox/state/Headroom.h"

namespace lockbox::testbed {

namespace {

// Nanoseconds to milliseconds, for display.
double Ms(int64_t ns) { return static_cast<double>(ns) * 1e-6; }

}  // namespace

void Testbed::DrawPanels() {
    DrawLabels();
    if (!showPanel_) return;
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(windowWidth_) - static_cast<float>(kPanelWidth), 0.0f));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(kPanelWidth), static_cast<float>(windowHeight_)));
    ImGui::Begin("lockbox testbed", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    // Sliders and fields take 55 % of the width, leaving room for their labels.
    ImGui::PushItemWidth(ImGui::GetContentRegionAvail().x * 0.55f);
    ScenePanel();
    ControlPanel();
    DrawPanel();
    StatsPanel();
    ReplayPanel();
    SideBySidePanel();
    ImGui::PopItemWidth();
    ImGui::End();
}

void Testbed::ScenePanel() {
    if (mode_ == ViewMode::replay && viewer_.IsOpen()) {
        // The views show the replay: its game and recorded settings replace the scene list.
        const replay::ReplayFile& f = viewer_.File();
        ImGui::Text("replay of %s", f.gameName.c_str());
        ImGui::Text("%d frames, %zu keyframes, %u Hz, %u/%u iterations", f.frameCount, f.keyframes.size(),
                    f.header.tickRate, f.header.velocityIterations, f.header.positionIterations);
        return;
    }
    const auto& catalog = SceneCatalog();
    if (catalog.empty()) return;
    const CatalogEntry& current = catalog[static_cast<size_t>(sceneIndex_)];
    const bool fromFile = primary_.SceneFile() != nullptr;
    ImGui::SetNextItemWidth(-1.0f);
    if (ImGui::BeginCombo("##scene", fromFile ? primary_.SceneName().c_str() : current.name.c_str())) {
        bool libraryDone = false;
        for (size_t i = 0; i < catalog.size(); ++i) {
            if (!catalog[i].library && !libraryDone) {
                ImGui::Separator();
                ImGui::TextDisabled("testbed-only scenes");
                libraryDone = true;
            }
            if (ImGui::Selectable(catalog[i].name.c_str(), static_cast<int>(i) == sceneIndex_))
                SelectScene(catalog[i].name);
        }
        ImGui::EndCombo();
    }
    if (fromFile) {
        ImGui::TextWrapped("scene file, %d bodies, %d joints", primary_.World().GetBodyCount(),
                           primary_.World().GetJointCount());
    } else {
        ImGui::TextWrapped("%s%s", current.summary.c_str(), current.library ? "" : " (testbed-only)");
    }
    SceneFilePanel();
}

void Testbed::SceneFilePanel() {
    if (mode_ != ViewMode::live) return;
    if (!ImGui::CollapsingHeader("Scene files (b2dJson)")) return;
    ImGui::InputText("File", sceneFilePath_, sizeof sceneFilePath_);
    ImGui::SameLine();
    if (ImGui::Button("Open")) OpenSceneFile(sceneFilePath_);
    // The picker: the .json files in the folder of the path above, listed again when it changes.
    const std::filesystem::path folder = std::filesystem::path(sceneFilePath_).parent_path();
    if (folder.string() != listedFolder_) {
        listedFolder_ = folder.string();
        folderFiles_.clear();
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(folder.empty() ? "." : folder, ec)) {
            if (entry.path().extension() == ".json") folderFiles_.push_back(entry.path().filename().string());
        }
        std::sort(folderFiles_.begin(), folderFiles_.end());
    }
    if (!folderFiles_.empty() &&
        ImGui::BeginListBox("##files", ImVec2(-1.0f, 6 * ImGui::GetTextLineHeightWithSpacing()))) {
        for (const std::string& name : folderFiles_) {
            const std::string full = (folder / name).string();
            if (ImGui::Selectable(name.c_str(), primary_.SceneName() == std::string(kSceneFilePrefix) + full)) {
                std::snprintf(sceneFilePath_, sizeof sceneFilePath_, "%s", full.c_str());
                OpenSceneFile(full);
            }
        }
        ImGui::EndListBox();
    }
    ImGui::InputText("Save as", savePath_, sizeof savePath_);
    ImGui::SameLine();
    if (ImGui::Button("Save")) SaveWorld(savePath_);
    if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
}

void Testbed::SettingsEditor(StepSettings& s, bool locked, const char* id) {
    ImGui::PushID(id);
    ImGui::BeginDisabled(locked);
    ImGui::SliderInt("Velocity iterations", &s.velocityIterations, 0, 50);
    ImGui::SliderInt("Position iterations", &s.positionIterations, 0, 50);
    ImGui::SliderInt("Hz", &s.hz, 5, 240);
    ImGui::Checkbox("Sleep", &s.sleep);
    ImGui::SameLine();
    ImGui::Checkbox("Warm starting", &s.warmStarting);
    ImGui::Checkbox("Continuous", &s.continuous);
    ImGui::SameLine();
    ImGui::Checkbox("Sub-stepping", &s.subStepping);
    ImGui::EndDisabled();
    ImGui::Checkbox("Headroom telemetry", &s.headroom);
    ImGui::PopID();
}

void Testbed::ControlPanel() {
    if (mode_ != ViewMode::live) return;  // a replay's settings are in its file
    if (!ImGui::CollapsingHeader("Controls", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Checkbox("Pause (P)", &paused_);
    ImGui::SameLine();
    if (ImGui::Button("Single step (O)")) paused_ = stepOnce_ = true;
    ImGui::SameLine();
    if (ImGui::Button("Restart (R)")) RestartLive();
    if (!primary_.Loaded()) return;
    StepSettings& s = primary_.Settings();
    // A recording fixes the step settings in its header: they stay locked until it stops.
    SettingsEditor(s, primary_.Recording(), "A");
    if (sideBySide_ && secondary_.Loaded()) {
        // B follows A except for its iterations.
        StepSettings& b = secondary_.Settings();
        const int vel = b.velocityIterations, pos = b.positionIterations;
        b = s;
        b.velocityIterations = vel;
        b.positionIterations = pos;
    }
}

void Testbed::DrawPanel() {
    if (!ImGui::CollapsingHeader("Draw", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Checkbox("Shapes", &options_.shapes);
    ImGui::SameLine();
    ImGui::Checkbox("Joints", &options_.joints);
    ImGui::SameLine();
    ImGui::Checkbox("AABBs", &options_.aabbs);
    ImGui::Checkbox("Pairs", &options_.pairs);
    ImGui::SameLine();
    ImGui::Checkbox("Centres of mass", &options_.centersOfMass);
    ImGui::Checkbox("Labels", &options_.labels);
    ImGui::SameLine();
    if (ImGui::Button("Fit view (Home)")) FitView();
}

void Testbed::WorldStats(b2World& world, uint64 hash, bool telemetry) {
    int awake = 0;
    for (b2Body* b = world.GetBodyList(); b; b = b->GetNext())
        if (b->GetType() != b2_staticBody && b->IsAwake()) ++awake;
    ImGui::Text("bodies %d (awake %d)  contacts %d", world.GetBodyCount(), awake, world.GetContactCount());
    ImGui::Text("joints %d  proxies %d", world.GetJointCount(), world.GetProxyCount());
    ImGui::Text("state hash %016" PRIx64, static_cast<uint64_t>(hash));

    const b2Profile& p = world.GetProfile();
    ImGui::Separator();
    ImGui::Text("step %.3f ms  collide %.3f  solve %.3f", Ms(p.stepNs), Ms(p.collideNs), Ms(p.solveNs));
    ImGui::Text("  init %.3f  velocity %.3f  position %.3f", Ms(p.solveInitNs), Ms(p.solveVelocityNs),
                Ms(p.solvePositionNs));
    ImGui::Text("  broad-phase %.3f  TOI %.3f", Ms(p.broadphaseNs), Ms(p.solveTOINs));
    ImGui::Text("pairs %d  contacts updated %d  islands %d", p.pairsFound, p.contactsUpdated, p.islandsSolved);
    ImGui::Text("TOI calls %d  events %d  sub-steps %d", p.toiCalls, p.toiEvents, p.toiSubSteps);

    ImGui::Separator();
    // The telemetry of the last step when on; otherwise a walk of the state shown.
    const b2Headroom h = telemetry ? p.headroom : b2MeasureHeadroom(world);
    const b2HeadroomClass tight = h.Tightest();
    ImGui::Text("headroom (%s), saturations %" PRId64 " (world %" PRIu64 ")", telemetry ? "telemetry" : "measured",
                h.saturations, static_cast<uint64_t>(world.GetSaturationCount()));
    if (ImGui::BeginTable("headroom", 2)) {
        ImGui::TableSetupColumn("class", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("angular_velocity *").x);
        ImGui::TableSetupColumn("share", ImGuiTableColumnFlags_WidthStretch);
        for (int32 c = 0; c < static_cast<int32>(b2HeadroomClass::e_count); ++c) {
            const auto cls = static_cast<b2HeadroomClass>(c);
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%s%s", b2HeadroomClassName(cls), cls == tight ? " *" : "");
            ImGui::TableNextColumn();
            char label[32];
            std::snprintf(label, sizeof label, "%.4f %%", 100.0 * h[cls].Fraction());
            ImGui::ProgressBar(static_cast<float>(h[cls].Fraction()), ImVec2(-1.0f, 0.0f), label);
        }
        ImGui::EndTable();
    }
}

void Testbed::StatsPanel() {
    if (!ImGui::CollapsingHeader("Text", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (mode_ == ViewMode::replay) {
        if (viewer_.IsOpen()) WorldStats(viewer_.World(), viewer_.Hash(), false);
    } else if (primary_.Loaded()) {
        WorldStats(primary_.World(), primary_.Hash(), primary_.Settings().headroom && primary_.Frame() > 0);
    }
}

void Testbed::ReplayPanel() {
    if (!ImGui::CollapsingHeader("Replay", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::SetNextItemWidth(-1.0f);
    ImGui::InputText("##path", replayPath_, sizeof replayPath_);
    if (mode_ == ViewMode::live) {
        if (!primary_.Recording()) {
            if (ImGui::Button("Record (restarts the scene)")) StartRecording(replayPath_);
        } else {
            ImGui::Text("recording: %d frames", primary_.RecordedFrames());
            ImGui::SameLine();
            if (ImGui::Button("Stop")) StopRecording();
        }
        ImGui::SameLine();
        ImGui::BeginDisabled(primary_.Recording());
        if (ImGui::Button("Open")) OpenReplay(replayPath_);
        ImGui::EndDisabled();
    } else {
        if (ImGui::Button("Close (back to live)")) CloseReplay();
        if (viewer_.IsOpen()) {
            int frame = viewer_.Frame();
            ImGui::SetNextItemWidth(-1.0f);
            if (ImGui::SliderInt("##frame", &frame, 0, viewer_.FrameCount())) SeekReplay(frame);
            if (ImGui::Button(replayPlaying_ ? "Pause (P)" : "Play (P)")) replayPlaying_ = !replayPlaying_;
            ImGui::SameLine();
            if (ImGui::Button("Step (O)")) stepOnce_ = true;
            ImGui::SameLine();
            if (ImGui::Button("Verify")) VerifyReplay();
            ImGui::SameLine();
            if (ImGui::Button("Jump to divergence")) JumpToDivergence();
            FaultInjector& fault = viewer_.Fault();
            ImGui::Checkbox("Inject a fault", &fault.enabled);
            ImGui::BeginDisabled(!fault.enabled);
            ImGui::SetNextItemWidth(90.0f);
            ImGui::InputInt("frame", &fault.frame);
            ImGui::SameLine();
            ImGui::SetNextItemWidth(110.0f);
            if (ImGui::BeginCombo("stage", replay::StageName(static_cast<uint32>(fault.stage)))) {
                for (uint32 st = 0; st < replay::kStagesPerFrame; ++st)
                    if (ImGui::Selectable(replay::StageName(st), static_cast<int32>(st) == fault.stage))
                        fault.stage = static_cast<int32>(st);
                ImGui::EndCombo();
            }
            ImGui::EndDisabled();
            if (!checkText_.empty()) ImGui::TextWrapped("%s", checkText_.c_str());
        }
    }
    if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
}

void Testbed::SideBySidePanel() {
    if (!ImGui::CollapsingHeader("Side by side", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::BeginDisabled(mode_ != ViewMode::live);
    bool on = sideBySide_;
    if (ImGui::Checkbox("Same scene at a second accuracy (right view)", &on)) SetSideBySide(on);
    ImGui::EndDisabled();
    ImGui::SliderInt("B velocity iterations", &iterationsB_[0], 0, 50);
    ImGui::SliderInt("B position iterations", &iterationsB_[1], 0, 50);
    if (!sideBySide_ || !secondary_.Loaded()) return;
    secondary_.Settings().velocityIterations = iterationsB_[0];
    secondary_.Settings().positionIterations = iterationsB_[1];
    const bool same = primary_.Hash() == secondary_.Hash();
    ImGui::Text("A %016" PRIx64 "\nB %016" PRIx64 "  %s", static_cast<uint64_t>(primary_.Hash()),
                static_cast<uint64_t>(secondary_.Hash()), same ? "same state" : "states differ");
}

}  // namespace lockbox::testbed
