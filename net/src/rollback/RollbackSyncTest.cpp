// SyncTestSession: a WorldGame through core's lockbox::SyncTest (RollbackSyncTest.h).

#include "lockbox/net/RollbackSyncTest.h"

#include <algorithm>
#include <string>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/state/WorldGame.h"
#include "lockbox/state/WorldHash.h"
#include "session/SessionCommon.h"

namespace lockbox::net {

struct SyncTestSession::Impl {
    b2World& world;
    WorldGame& game;
    SyncTestInputSource source;
    SyncTestSessionConfig config;
    // Inputs by frame: a re-simulation must see exactly the first run's inputs even when the
    // source is not a pure function of the frame.
    std::vector<std::vector<uint8_t>> inputs;

    Impl(b2World& w, WorldGame& g, SyncTestInputSource s, SyncTestSessionConfig c)
        : world(w), game(g), source(std::move(s)), config(c) {}

    SyncTestRequestCounts counts;

    const std::vector<uint8_t>& InputsFor(int32_t frame) {
        const size_t f = static_cast<size_t>(frame < 0 ? 0 : frame);
        const size_t row = static_cast<size_t>(config.players) * config.inputBytes;
        while (inputs.size() <= f) {
            std::vector<uint8_t> in(row, 0);
            if (source) source(static_cast<int32_t>(inputs.size()), in);
            inputs.push_back(std::move(in));
        }
        return inputs[f];
    }
    // Wrong inputs of a mispredicted branch: seeded bytes (splitmix64 of the seed and frame).
    std::vector<uint8_t> WrongInputs(int32_t frame) const {
        std::vector<uint8_t> out(static_cast<size_t>(config.players) * config.inputBytes);
        uint64_t state = config.seed ^ (static_cast<uint64_t>(frame) * 0xD1B54A32D192ED03ull);
        for (size_t i = 0; i < out.size(); ++i) {
            uint64_t z = (state += 0x9E3779B97F4A7C15ull);
            z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
            z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
            out[i] = static_cast<uint8_t>(z ^ (z >> 31));
        }
        return out;
    }
    AdvanceRequest MakeAdvance(int32_t frame, bool wrong) {
        AdvanceRequest a;
        a.frame = frame;
        a.inputs = wrong ? WrongInputs(frame) : InputsFor(frame);
        a.status.assign(config.players, wrong ? InputStatus::e_predicted : InputStatus::e_confirmed);
        return a;
    }
};

SyncTestSession::SyncTestSession(b2World& world, WorldGame& game, SyncTestInputSource inputs,
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
    c.inputBytes = m_impl->config.players * m_impl->config.inputBytes;
    c.step = m_impl->config.step;
    // The session's own input memory, so Run and RunRequests see the same bytes per frame.
    SyncTest test(
        m_impl->world, m_impl->game,
        [impl = m_impl.get()](int32 frame, std::span<uint8> out) {
            const std::vector<uint8_t>& in = impl->InputsFor(frame);
            std::copy(in.begin(), in.end(), out.begin());
        },
        c);
    return test.Run(frames);
}

const SyncTestRequestCounts& SyncTestSession::RequestCounts() const noexcept { return m_impl->counts; }

SyncTestResult SyncTestSession::RunRequests(int32_t frames) {
    Impl& m = *m_impl;
    WorldGameAdapter adapter(m.world, m.game, m.config.step, m.config.checkDistance + 2);
    return RunRequests(frames, [&adapter](std::span<const RollbackRequest> requests, const RollbackHashReport& report) {
        return adapter.Execute(requests, report);
    });
}

SyncTestResult SyncTestSession::RunRequests(int32_t frames, const SyncTestExecutor& executor) {
    Impl& m = *m_impl;
    SyncTestResult result;
    if (frames < 0) frames = 0;
    const auto k = static_cast<int32_t>(m.config.checkDistance);
    const size_t ring = static_cast<size_t>(k) + 1;
    std::vector<uint64_t> first(static_cast<size_t>(frames) + 1, 0);
    std::vector<uint8_t> known(static_cast<size_t>(frames) + 1, 0);
    // The first run's breakdown of the last k + 1 frames, taken when their hashes are reported
    // (the world is at that frame then), to name what differs on a mismatch.
    std::vector<b2WorldHashReport> details(ring);
    bool checking = false;
    const RollbackHashReport report = [&](int32_t frame, uint64_t hash) {
        if (!result.ok || frame < 0 || frame > frames) return;
        const auto at = static_cast<size_t>(frame);
        if (!checking) {
            first[at] = hash;
            known[at] = 1;
            details[at % ring] = b2WorldHashDetailed(m.world);
            return;
        }
        if (known[at] == 0 || first[at] == hash) return;
        result.ok = false;
        result.firstBadFrame = frame;
        result.expected = first[at];
        result.actual = hash;
        result.where = b2CompareHashReports(details[at % ring], b2WorldHashDetailed(m.world));
        const bool worldDiffers = result.where.category != b2HashCategory::e_count;
        result.message = "state after frame " + std::to_string(frame) + " differs on re-simulation: " +
                         (worldDiffers ? "category " + std::string(b2HashCategoryName(result.where.category)) +
                                             ", body " + std::to_string(result.where.bodyId)
                                       : std::string("user state"));
    };
    const RollbackHashReport ignore = [](int32_t, uint64_t) {};
    std::vector<RollbackRequest> batch;
    auto execute = [&](const RollbackHashReport& r) {
        for (const RollbackRequest& q : batch) {
            if (std::holds_alternative<SaveState>(q)) ++m.counts.saves;
            if (std::holds_alternative<LoadState>(q)) ++m.counts.loads;
            if (const auto* a = std::get_if<AdvanceRequest>(&q)) {
                ++m.counts.advances;
                if (!a->status.empty() && a->status[0] == InputStatus::e_predicted) ++m.counts.predictedAdvances;
            }
        }
        if (!executor(batch, r) && result.ok) {
            result.ok = false;
            result.message = "the executor failed a batch of requests";
        }
        batch.clear();
        return result.ok;
    };
    // Re-simulates frames [from, to) from the state saved at `from`; wrong inputs with no
    // hashes asked, or the right ones with every hash checked.
    auto branch = [&](int32_t from, int32_t to, bool wrong) {
        batch.emplace_back(LoadState{from});
        for (int32_t g = from; g < to; ++g) {
            batch.emplace_back(m.MakeAdvance(g, wrong));
            batch.emplace_back(SaveState{g + 1, !wrong});
        }
    };
    batch.emplace_back(SaveState{0, true});
    if (!execute(report)) return result;
    for (int32_t f = 0; f < frames; ++f) {
        checking = false;
        batch.emplace_back(m.MakeAdvance(f, false));
        batch.emplace_back(SaveState{f + 1, true});
        if (!execute(report)) return result;
        ++result.framesSimulated;
        if (f + 1 < k) continue;
        const int32_t from = f + 1 - k;
        if (m.config.mispredict) {
            branch(from, f + 1, true);
            if (!execute(ignore)) return result;
        }
        checking = true;
        branch(from, f + 1, false);
        if (!execute(report)) return result;
        ++result.rollbacks;
        result.framesResimulated += k;
    }
    return result;
}

}  // namespace lockbox::net
