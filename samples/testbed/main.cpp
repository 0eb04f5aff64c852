// lockbox_testbed: the interactive viewer of the manual's "The Testbed", with
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
#include <string>

#include "App.h"
#include "Headless.h"
#include "SceneCatalog.h"
#include "lockbox/scenes/SceneFileScene.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox::testbed;

namespace {

constexpr const char* kUsage =
    "usage: lockbox_testbed [--scene NAME | --scene-file FILE.json] [--steps N] [--side-by-side]\n"
    "                       [--paused]\n"
    "       lockbox_testbed --scene NAME --steps N --screenshot FILE.png [--size WxH] [--no-panel]\n"
    "                       [--side-by-side] [--record FILE.lbr]\n"
    "       lockbox_testbed --replay FILE.lbr [--frame F] [--inject FRAME:STAGE] [--verify] [--bisect]\n"
    "                       --screenshot FILE.png   (STAGE 0..4: inputs collide solve broadphase toi)\n"
    "       lockbox_testbed --check FILE.png   (exit 0 when the image has two colours or more)\n"
    "       lockbox_testbed --list\n";

int List() {
    for (const CatalogEntry& e : SceneCatalog())
        std::printf("%-26s %s%s\n", e.name.c_str(), e.library ? "" : "[testbed] ", e.summary.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    HeadlessOptions headless;
    AppOptions app;
    std::string check;
    bool list = false;
    lockbox::cli::OptionReader args("lockbox_testbed", argc, argv);
    while (args.Next()) {
        if (args.Is("--scene")) {
            if (args.Text(app.scene)) headless.scene = app.scene;
        } else if (args.Is("--scene-file")) {
            // A b2dJson file, checked here so that a bad one is reported with its error.
            std::string path;
            if (!args.Text(path)) continue;
            lockbox::scenefile::SceneResult error;
            if (!lockbox::scenes::SceneFileScene::Open(path, &error)) {
                std::fprintf(stderr, "%s: %s\n", path.c_str(), error.Describe().c_str());
                return 2;
            }
            app.scene = headless.scene = std::string(kSceneFilePrefix) + path;
        } else if (args.Is("--steps")) {
            if (args.Int(0, 100000000, app.steps)) headless.steps = app.steps;
        } else if (args.Is("--screenshot")) {
            args.Text(headless.output);
        } else if (args.Is("--size")) {
            args.IntPair('x', "WxH with each side in 64..8192", 64, 8192, 64, 8192, headless.width, headless.height);
        } else if (args.Is("--no-panel")) {
            headless.panel = false;
        } else if (args.Is("--side-by-side")) {
            app.sideBySide = headless.sideBySide = true;
        } else if (args.Is("--paused")) {
            app.paused = true;
        } else if (args.Is("--record")) {
            args.Text(headless.record);
        } else if (args.Is("--replay")) {
            args.Text(headless.replay);
        } else if (args.Is("--frame")) {
            args.Int(0, 100000000, headless.replayFrame);
        } else if (args.Is("--inject")) {
            args.IntPair(':', "FRAME:STAGE with STAGE in 0..4", 0, 100000000, 0, 4, headless.injectFrame,
                         headless.injectStage);
        } else if (args.Is("--verify")) {
            headless.verify = true;
        } else if (args.Is("--bisect")) {
            headless.bisect = true;
        } else if (args.Is("--check")) {
            args.Text(check);
        } else if (args.Is("--list")) {
            list = true;
        } else {
            args.Unknown();
        }
    }
    if (args.Failed()) return args.Fail(kUsage);
    if (list) return List();
    if (!check.empty()) return CheckImage(check);
    if (!headless.output.empty()) {
        if (headless.scene.empty() && headless.replay.empty()) {
            args.Refuse("--screenshot needs --scene, --scene-file or --replay");
            return args.Fail(kUsage);
        }
        return RunHeadless(headless);
    }
    if (!app.scene.empty() && CatalogIndex(app.scene) < 0 && !IsSceneFileName(app.scene)) {
        std::fprintf(stderr, "unknown scene '%s' (--list shows them)\n", app.scene.c_str());
        return 2;
    }
    return RunApp(app);
}
