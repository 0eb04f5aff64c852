// Loading, scrubbing, verifying and bisecting a replay file.
#include "ReplayViewer.h"

#include <cstdio>

namespace lockbox::testbed {

void FaultInjector::OnStage(int32 atFrame, uint32 atStage, b2World& world) {
    if (!enabled || atFrame != frame || static_cast<int32>(atStage) != stage) return;
    for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() != b2_dynamicBody) continue;
        // One raw unit: the smallest change the format can make.
        b->SetLinearVelocity(b->GetLinearVelocity() + b2Vec2(Fixed::FromRaw(1), Fixed()));
        return;
    }
}

bool ReplayViewer::Open(const std::string& path, std::string& message) {
    replay::ReplayFile file;
    if (replay::Error e = replay::LoadReplay(path, file); !e.ok()) {
        message = path + ": " + e.Describe();
        return false;
    }
    ReplayGame game = MakeReplayGame(file.gameName);
    if (!game.game) {
        message = path + ": game \"" + file.gameName + "\" is not a scene the testbed knows";
        return false;
    }
    Close();
    // The player keeps references to the file and the game: they live in this object.
    file_ = std::move(file);
    game_ = std::move(game);
    path_ = path;
    player_ = std::make_unique<replay::Player>(file_, *game_.world, *game_.game);
    player_->SetStageHook(&fault_);
    if (replay::Error e = player_->Reset(); !e.ok()) {
        message = path + ": " + e.Describe();
        Close();
        return false;
    }
    Refresh();
    char buf[160];
    std::snprintf(buf, sizeof buf, " (%s, %d frames, %zu keyframes, %u Hz, %u/%u iterations)", file_.gameName.c_str(),
                  file_.frameCount, file_.keyframes.size(), file_.header.tickRate, file_.header.velocityIterations,
                  file_.header.positionIterations);
    message = "opened " + path + buf;
    return true;
}

void ReplayViewer::Close() {
    player_.reset();
    game_ = ReplayGame{};
    file_ = replay::ReplayFile{};
    path_.clear();
    hash_ = 0;
}

void ReplayViewer::Refresh() { hash_ = World().Hash(); }

bool ReplayViewer::MatchesRecording() const noexcept {
    const int32 f = player_->Frame();
    if (f == 0) return hash_ == file_.seed.hash;
    return !file_.HasHash(f - 1) || file_.hashes[static_cast<size_t>(f - 1)] == hash_;
}

bool ReplayViewer::Seek(int32 frame, std::string& message) {
    if (!IsOpen()) return false;
    if (replay::Error e = player_->Seek(frame); !e.ok()) {
        message = "seek failed: " + e.Describe();
        return false;
    }
    Refresh();
    return true;
}

bool ReplayViewer::StepForward() {
    if (!IsOpen() || !player_->Step()) return false;
    Refresh();
    return true;
}

bool ReplayViewer::MakeChecker(Checker& out) {
    out.game = MakeReplayGame(file_.gameName);
    if (!out.game.game) return false;
    out.player = std::make_unique<replay::Player>(file_, *out.game.world, *out.game.game);
    out.player->SetStageHook(&fault_);
    return true;
}

std::string ReplayViewer::Verify() {
    Checker checker;
    if (!IsOpen() || !MakeChecker(checker)) return "no replay";
    const replay::VerifyResult r = checker.player->Verify();
    if (!r.error.ok()) return "cannot play: " + r.error.Describe();
    return r.message;
}

std::string ReplayViewer::BisectAndJump() {
    Checker checker;
    if (!IsOpen() || !MakeChecker(checker)) return "no replay";
    const replay::BisectResult r = replay::Bisect(*checker.player);
    std::string text = r.Describe();
    if (r.error.ok() && r.diverged && r.frame >= 0) {
        std::string message;
        // The state before the divergent frame: the next single step shows it going wrong.
        if (!Seek(r.frame, message)) text += "\n" + message;
    }
    return text;
}

}  // namespace lockbox::testbed
