// lockbox_testbed: the interactive viewer of the manual's "The Testbed" (issue 12), with
// lockbox's own tools: state hash, headroom, replays and side-by-side accuracy.
//
//   lockbox_testbed [--scene NAME | --scene-file FILE.json] [--steps N] [--side-by-side] [--paused]
//   lockbox_testbed --scene NAME --steps N --screenshot FILE.png [--size WxH] [--no-panel]
//                   [--side-by-side]
//   lockbox_testbed ... --screenshot FILE.png --record FILE.lbr         (record the N steps)
//   lockbox_testbed --replay FILE.lbr [--frame F] [--inject F:S] [--verify] [--bisect]
//                   --screenshot FILE.png
//   lockbox_testbed --check FILE.png
//   lockbox_testbed --list
//
// See docs/testbed.md for the keys and panels.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "App.h"
#include "Headless.h"
#include "SceneCatalog.h"
#include "lockbox/scenes/SceneFileScene.h"

using namespace lockbox::testbed;

namespace {

int Usage() {
    std::fprintf(stderr,
                 "usage: lockbox_testbed [--scene NAME | --scene-file FILE.json] [--steps N] [--side-by-side]\n"
                 "                       [--paused]\n"
                 "       lockbox_testbed --scene NAME --steps N --screenshot FILE.png [--size WxH] [--no-panel]\n"
                 "                       [--side-by-side] [--record FILE.lbr]\n"
                 "       lockbox_testbed --replay FILE.lbr [--frame F] [--inject FRAME:STAGE] [--verify] [--bisect]\n"
                 "                       --screenshot FILE.png   (STAGE 0..4: inputs collide solve broadphase toi)\n"
                 "       lockbox_testbed --check FILE.png   (exit 0 when the image has two colours or more)\n"
                 "       lockbox_testbed --list\n");
    return 2;
}

int List() {
    for (const CatalogEntry& e : SceneCatalog())
        std::printf("%-26s %s%s\n", e.name.c_str(), e.library ? "" : "[testbed] ", e.summary.c_str());
    return 0;
}

// Parses a non-negative integer; false on anything else.
bool ParseCount(const char* text, int& out) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < 0 || v > 100000000) return false;
    out = static_cast<int>(v);
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    HeadlessOptions headless;
    AppOptions app;
    std::string check;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool more = i + 1 < argc;
        if (a == "--scene" && more) {
            app.scene = headless.scene = argv[++i];
        } else if (a == "--scene-file" && more) {
            // A b2dJson file, checked here so that a bad one is reported with its error.
            const std::string path = argv[++i];
            lockbox::scenefile::SceneResult error;
            if (!lockbox::scenes::SceneFileScene::Open(path, &error)) {
                std::fprintf(stderr, "%s: %s\n", path.c_str(), error.Describe().c_str());
                return 2;
            }
            app.scene = headless.scene = std::string(kSceneFilePrefix) + path;
        } else if (a == "--steps" && more) {
            if (!ParseCount(argv[++i], app.steps)) return Usage();
            headless.steps = app.steps;
        } else if (a == "--screenshot" && more) {
            headless.output = argv[++i];
        } else if (a == "--size" && more) {
            if (std::sscanf(argv[++i], "%dx%d", &headless.width, &headless.height) != 2 || headless.width < 64 ||
                headless.height < 64 || headless.width > 8192 || headless.height > 8192)
                return Usage();
        } else if (a == "--no-panel") {
            headless.panel = false;
        } else if (a == "--side-by-side") {
            app.sideBySide = headless.sideBySide = true;
        } else if (a == "--paused") {
            app.paused = true;
        } else if (a == "--record" && more) {
            headless.record = argv[++i];
        } else if (a == "--replay" && more) {
            headless.replay = argv[++i];
        } else if (a == "--frame" && more) {
            if (!ParseCount(argv[++i], headless.replayFrame)) return Usage();
        } else if (a == "--inject" && more) {
            if (std::sscanf(argv[++i], "%d:%d", &headless.injectFrame, &headless.injectStage) != 2 ||
                headless.injectFrame < 0 || headless.injectStage < 0 || headless.injectStage > 4)
                return Usage();
        } else if (a == "--verify") {
            headless.verify = true;
        } else if (a == "--bisect") {
            headless.bisect = true;
        } else if (a == "--check" && more) {
            check = argv[++i];
        } else if (a == "--list") {
            return List();
        } else {
            return Usage();
        }
    }
    if (!check.empty()) return CheckImage(check);
    if (!headless.output.empty()) {
        if (headless.scene.empty() && headless.replay.empty()) return Usage();
        return RunHeadless(headless);
    }
    if (!app.scene.empty() && CatalogIndex(app.scene) < 0 && !IsSceneFileName(app.scene)) {
        std::fprintf(stderr, "unknown scene '%s' (--list shows them)\n", app.scene.c_str());
        return 2;
    }
    return RunApp(app);
}
