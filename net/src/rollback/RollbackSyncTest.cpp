// SyncTestSession: a replay::Game through core's lockbox::SyncTest (RollbackSyncTest.h).

#include "lockbox/net/RollbackSyncTest.h"

#include <algorithm>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/replay/Game.h"
#include "session/SessionCommon.h"

namespace lockbox::net {

struct SyncTestSession::Impl : SyncTestGame {
    b2World& world;
    replay::Game& game;
    SyncTestInputSource source;
    SyncTestSessionConfig config;
    // Inputs by frame: a re-simulation must see exactly the first run's inputs even when the
    // source is not a pure function of the frame.
    std::vector<std::vector<uint8_t>> inputs;

    Impl(b2World& w, replay::Game& g, SyncTestInputSource s, SyncTestSessionConfig c)
        : world(w), game(g), source(std::move(s)), config(c) {}

    void Advance(b2World& w, int32 frame) override {
        const size_t f = static_cast<size_t>(frame < 0 ? 0 : frame);
        const size_t row = static_cast<size_t>(config.players) * config.inputBytes;
        while (inputs.size() <= f) {
            std::vector<uint8_t> in(row, 0);
            if (source) source(static_cast<int32_t>(inputs.size()), in);
            inputs.push_back(std::move(in));
        }
        StepConfirmedFrame(w, game, frame, inputs[f], config.step.tickRate, config.step.velocityIterations,
                           config.step.positionIterations);
    }
    void SaveUserState(std::vector<uint8>& out) const override { game.SaveUserState(out); }
    void LoadUserState(std::span<const uint8> in) override { game.LoadUserState(in); }
};

SyncTestSession::SyncTestSession(b2World& world, replay::Game& game, SyncTestInputSource inputs,
                                 SyncTestSessionConfig config)
    : m_impl(std::make_unique<Impl>(world, game, std::move(inputs), config)) {
    SyncTestSessionConfig& c = m_impl->config;
    c.players = std::clamp<uint32_t>(c.players, 1, kRollbackMaxPlayers);
    c.inputBytes = std::clamp<uint32_t>(c.inputBytes, 1, kRollbackMaxInputBytes);
    c.checkDistance = std::clamp<uint32_t>(c.checkDistance, 1, kRollbackMaxWindow);
}

SyncTestSession::~SyncTestSession() = default;

SyncTestSessionConfig SyncTestConfigFrom(const RollbackConfig& config, WorldStepSettings step, bool mispredict) {
    SyncTestSessionConfig c;
    c.players = config.players;
    c.inputBytes = config.inputBytes;
    c.checkDistance = config.checkDistance;
    c.mispredict = mispredict;
    c.step = step;
    return c;
}

SyncTestResult SyncTestSession::Run(int32_t frames) {
    SyncTestConfig c;
    c.checkDistance = static_cast<int32>(m_impl->config.checkDistance);
    c.mispredict = m_impl->config.mispredict;
    c.seed = m_impl->config.seed;
    c.frames = m_impl->config.restore == SyncTestRestore::e_frames;
    SyncTest test(m_impl->world, *m_impl, c);
    return test.Run(frames);
}

}  // namespace lockbox::net
