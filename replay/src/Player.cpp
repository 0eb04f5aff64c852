// Player: seed and keyframe restores, frame stepping, verification.
#include "lockbox/replay/Player.h"

#include <cstdio>

#include "StageHasher.h"

namespace lockbox::replay {

namespace {
std::string Hex(uint64 v) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
}
}  // namespace

Player::Player(const ReplayFile& file, b2World& world, Game& game) : file_(file), world_(world), game_(game) {}

Player::~Player() = default;

Error Player::Restore(const Keyframe& keyframe) {
    const b2RestoreResult r = world_.Restore(keyframe.world);
    ++restores_;
    if (!r.ok()) {
        Error e;
        e.code = ErrorCode::e_badSnapshot;
        e.frame = keyframe.frame;
        e.message = std::string(keyframe.frame == 0 ? "seed" : "keyframe") +
                    " snapshot refused: " + b2SnapshotErrorName(r.error) + ": " + r.message;
        return e;
    }
    game_.LoadUserState(keyframe.user);
    frame_ = keyframe.frame;
    restored_ = true;
    return {};
}

Error Player::Reset() { return Restore(file_.seed); }

Error Player::Seek(int32 frame) {
    if (frame < 0 || frame > file_.frameCount) {
        Error e;
        e.code = ErrorCode::e_usage;
        e.frame = frame;
        e.message = "seek to frame " + std::to_string(frame) + " outside 0.." + std::to_string(file_.frameCount);
        return e;
    }
    const Keyframe& k = file_.NearestKeyframe(frame);
    // Stepping on from where we are is cheaper than a restore when no keyframe lies between.
    if (!restored_ || frame < frame_ || k.frame > frame_) {
        if (Error e = Restore(k)) return e;
    }
    while (frame_ < frame) Step();
    return {};
}

bool Player::Step() {
    if (AtEnd()) return false;
    const int32 frame = frame_;
    game_.Apply(world_, frame, file_.Inputs(frame));
    const Fixed dt = Fixed::FromRaw(file_.header.timeStepRaw);
    if (stageHashing_ || hook_ != nullptr) {
        detail::StageHasher stages;
        stages.hook = hook_;
        stages.hashing = stageHashing_;
        stages.BeginFrame(frame, world_);
        b2StepObserver* previous = world_.GetStepObserver();
        world_.SetStepObserver(&stages);
        world_.Step(dt, file_.header.velocityIterations, file_.header.positionIterations);
        world_.SetStepObserver(previous);
        for (uint32 i = 0; i < kStagesPerFrame; ++i) lastStages_[i] = stages.stages[i];
        for (uint32 i = 0; i < kSolvePhasesPerFrame; ++i) lastSolve_[i] = stages.solve[i];
    } else {
        world_.Step(dt, file_.header.velocityIterations, file_.header.positionIterations);
    }
    ++frame_;
    ++framesPlayed_;
    return true;
}

VerifyResult Player::Verify() {
    VerifyResult r;
    if (Error e = Reset()) {
        r.error = e;
        r.message = e.Describe();
        return r;
    }
    if (world_.Hash() != file_.seed.hash) {
        r.firstBadFrame = 0;
        r.expected = file_.seed.hash;
        r.actual = world_.Hash();
        r.message = "seed state hash differs after restore: expected " + Hex(r.expected) + ", got " + Hex(r.actual);
        return r;
    }
    while (!AtEnd()) {
        const int32 frame = frame_;
        Step();
        ++r.frames;
        if (!file_.HasHash(frame)) continue;
        const uint64 h = world_.Hash();
        ++r.hashesChecked;
        if (h != file_.hashes[static_cast<size_t>(frame)]) {
            r.firstBadFrame = frame;
            r.expected = file_.hashes[static_cast<size_t>(frame)];
            r.actual = h;
            r.finalHash = h;
            r.message = "DIVERGED at frame " + std::to_string(frame) + ": recorded " + Hex(r.expected) +
                        ", re-simulated " + Hex(r.actual);
            return r;
        }
    }
    r.finalHash = world_.Hash();
    if (r.finalHash != file_.finalHash) {
        r.firstBadFrame = file_.frameCount - 1;
        r.expected = file_.finalHash;
        r.actual = r.finalHash;
        r.message = "DIVERGED: final state after frame " + std::to_string(file_.frameCount - 1) + " recorded " +
                    Hex(r.expected) + ", re-simulated " + Hex(r.actual) + " (no stored hash before it differed)";
        return r;
    }
    r.ok = true;
    r.message = "OK frames=" + std::to_string(r.frames) + " hash=" + Hex(r.finalHash);
    return r;
}

}  // namespace lockbox::replay
