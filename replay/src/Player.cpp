// Player: seed and keyframe restores, frame stepping, verification.
#include "lockbox/replay/Player.h"

#include "HexText.h"
#include "StageHasher.h"

namespace lockbox::replay {

using detail::Hex;

Player::Player(const ReplayFile& file, b2World& world, Game& game) : m_file(file), m_world(world), m_game(game) {}

Player::~Player() = default;

Error Player::Restore(const Keyframe& keyframe) {
    const b2RestoreResult r = m_world.Restore(keyframe.world);
    ++m_restores;
    if (!r.ok()) {
        Error e;
        e.code = ErrorCode::e_badSnapshot;
        e.frame = keyframe.frame;
        e.message = std::string(keyframe.frame == 0 ? "seed" : "keyframe") +
                    " snapshot refused: " + b2SnapshotErrorName(r.error) + ": " + r.message;
        return e;
    }
    m_game.LoadUserState(keyframe.user);
    m_frame = keyframe.frame;
    m_restored = true;
    return {};
}

Error Player::Reset() { return Restore(m_file.seed); }

Error Player::Seek(int32 frame) {
    if (frame < 0 || frame > m_file.frameCount) {
        Error e;
        e.code = ErrorCode::e_usage;
        e.frame = frame;
        e.message = "seek to frame " + std::to_string(frame) + " outside 0.." + std::to_string(m_file.frameCount);
        return e;
    }
    const Keyframe& k = m_file.NearestKeyframe(frame);
    // Stepping on from where we are is cheaper than a restore when no keyframe lies between.
    if (!m_restored || frame < m_frame || k.frame > m_frame) {
        if (Error e = Restore(k); !e.ok()) return e;
    }
    while (m_frame < frame) Step();
    return {};
}

bool Player::Step() {
    if (AtEnd()) return false;
    const int32 frame = m_frame;
    m_game.Apply(m_world, frame, m_file.Inputs(frame));
    const Fixed dt = Fixed::FromRaw(m_file.header.timeStepRaw);
    if (m_stageHashing || m_hook != nullptr) {
        detail::StageHasher stages;
        stages.hook = m_hook;
        stages.hashing = m_stageHashing;
        stages.BeginFrame(frame, m_world);
        b2StepObserver* previous = m_world.GetStepObserver();
        m_world.SetStepObserver(&stages);
        m_world.Step(dt, m_file.header.velocityIterations, m_file.header.positionIterations);
        m_world.SetStepObserver(previous);
        for (uint32 i = 0; i < kStagesPerFrame; ++i) m_lastStages[i] = stages.stages[i];
        for (uint32 i = 0; i < kSolvePhasesPerFrame; ++i) m_lastSolve[i] = stages.solve[i];
    } else {
        m_world.Step(dt, m_file.header.velocityIterations, m_file.header.positionIterations);
    }
    ++m_frame;
    ++m_framesPlayed;
    return true;
}

VerifyResult Player::Verify() {
    VerifyResult r;
    if (Error e = Reset(); !e.ok()) {
        r.error = e;
        r.message = e.Describe();
        return r;
    }
    if (m_world.Hash() != m_file.seed.hash) {
        r.firstBadFrame = 0;
        r.expected = m_file.seed.hash;
        r.actual = m_world.Hash();
        r.message = "seed state hash differs after restore: expected " + Hex(r.expected) + ", got " + Hex(r.actual);
        return r;
    }
    while (!AtEnd()) {
        const int32 frame = m_frame;
        Step();
        ++r.frames;
        if (!m_file.HasHash(frame)) continue;
        const uint64 h = m_world.Hash();
        ++r.hashesChecked;
        if (h != m_file.hashes[static_cast<size_t>(frame)]) {
            r.firstBadFrame = frame;
            r.expected = m_file.hashes[static_cast<size_t>(frame)];
            r.actual = h;
            r.finalHash = h;
            r.message = "DIVERGED at frame " + std::to_string(frame) + ": recorded " + Hex(r.expected) +
                        ", re-simulated " + Hex(r.actual);
            return r;
        }
    }
    r.finalHash = m_world.Hash();
    if (r.finalHash != m_file.finalHash) {
        r.firstBadFrame = m_file.frameCount - 1;
        r.expected = m_file.finalHash;
        r.actual = r.finalHash;
        r.message = "DIVERGED: final state after frame " + std::to_string(m_file.frameCount - 1) + " recorded " +
                    Hex(r.expected) + ", re-simulated " + Hex(r.actual) + " (no stored hash before it differed)";
        return r;
    }
    r.ok = true;
    r.message = "OK frames=" + std::to_string(r.frames) + " hash=" + Hex(r.finalHash);
    return r;
}

}  // namespace lockbox::replay
