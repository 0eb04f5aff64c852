// The rollback match of the main demo (RollbackMatch.h). Two player threads, each owning its
// socket, world and session; the main thread only prints what they publish and, at the end,
// compares their final hashes.
#include "RollbackMatch.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <variant>
#include <vector>

#include "lockbox/net/LatencyTransport.h"
#include "lockbox/net/RollbackBudgetGuard.h"
#include "lockbox/net/RollbackPeer.h"
#include "lockbox/net/RollbackSession.h"
#include "lockbox/net/RollbackWorldAdapter.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::demo {

namespace {

using Clock = std::chrono::steady_clock;

/// What a player thread publishes.
struct Board {
    std::atomic<int32_t> frame{0}, confirmed{0};
    std::atomic<uint64_t> rollbacks{0}, resimulated{0}, resimNanos{0}, rollbackSteps{0};
    std::atomic<uint32_t> deepest{0}, inputDelay{0};
    std::atomic<bool> done{false}, failed{false}, desync{false};
    std::mutex lock;
    std::map<int32_t, uint64_t> finals;  // frame -> final hash (under lock)
};

void PlayerThread(uint32_t me, std::unique_ptr<net::UdpTransport> socket, net::PeerId other, const RollbackOptions o,
                  Board& board, Clock::time_point deadline) {
    // A long cable on loopback, so predictions miss and rollbacks happen: what this player
    // receives waits latencyMs first (the other player's transport delays the other way).
    net::LatencyProfile cable;
    cable.latencyMicros = static_cast<uint32_t>(o.latencyMs) * 1000;
    net::LatencyTransport transport(*socket, cable, o.seed * 1000 + me);
    replay::SceneGame game(o.scene);
    auto session = net::RollbackSessionBuilder()
                       .Players(2)
                       .InputBytes(replay::SceneInput::kBytes)
                       .LocalPlayer(me)
                       .InputDelay(static_cast<uint32_t>(o.inputDelay))
                       .PredictionWindow(static_cast<uint32_t>(o.window))
                       .DesyncInterval(30)
                       .Build();
    const auto& info = game.info();
    net::WorldGameAdapter adapter(
        game.world(), game,
        WorldStepSettings{static_cast<uint32_t>(info.hz), static_cast<uint32_t>(info.velocityIterations),
                          static_cast<uint32_t>(info.positionIterations)});
    net::RollbackPeerConfig cfg;
    cfg.matchId = 0x524F4C4Cu;
    cfg.remotes.push_back(net::RollbackRemote{other, {1 - me}});
    net::RollbackPeer peer(*session, transport, cfg);
    replay::ScriptedInputs script(o.seed * 1000 + me, 1);
    std::vector<uint8_t> input;
    bool pending = false;  // a drawn input the session has not taken yet
    std::unique_ptr<net::RollbackBudgetGuard> budget;
    if (o.budgetMs > 0) {
        net::RollbackBudgetConfig bc;
        bc.budgetMicros = static_cast<uint32_t>(o.budgetMs) * 1000;
        budget = std::make_unique<net::RollbackBudgetGuard>(bc, static_cast<uint32_t>(o.inputDelay));
    }
    const auto tick = std::chrono::microseconds(1000000 / 60);
    auto next = Clock::now();
    // Play past `frames` until both sides have confirmed it, then a little longer so the
    // other side hears our last inputs and hashes too.
    int32_t lingerTicks = 30;
    while (Clock::now() < deadline && lingerTicks > 0) {
        peer.Poll();
        if (!peer.WaitThisTick()) {
            if (!pending) script.Next(input);
            pending = session->AddLocalInput(me, input) == net::InputResult::e_alreadyAdded;
            const uint64_t resimBefore = session->Stats().framesResimulated;
            const auto reqs = session->AdvanceFrame();
            const bool rollback = std::any_of(reqs.begin(), reqs.end(), [](const net::RollbackRequest& r) {
                return std::holds_alternative<net::LoadState>(r);
            });
            const auto t0 = Clock::now();
            if (!adapter.Execute(*session, reqs)) board.failed = true;
            const auto nanos =
                static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count());
            if (rollback) {
                // Every Advance of a rollback batch (the re-simulated frames and the new one)
                // with its save: the cost per frame of catching up.
                board.rollbackSteps +=
                    static_cast<uint64_t>(std::count_if(reqs.begin(), reqs.end(), [](const net::RollbackRequest& r) {
                        return std::holds_alternative<net::AdvanceRequest>(r);
                    }));
                board.resimNanos += nanos;
            }
            if (budget) {
                // The guard picks the delay the other player should use; this player uses
                // the one the other asks for (docs/rollback.md, "The budget guard").
                const auto depth = static_cast<uint32_t>(session->Stats().framesResimulated - resimBefore);
                if (budget->Record(depth, static_cast<uint32_t>(std::min<uint64_t>(nanos / 1000, UINT32_MAX))))
                    peer.AskInputDelay(budget->Delay());
                const uint32_t wanted = std::max(static_cast<uint32_t>(o.inputDelay), peer.RemoteDelayWish());
                if (wanted != session->InputDelay()) session->SetInputDelay(wanted);
            }
        }
        peer.Flush();
        const net::RollbackStats& s = session->Stats();
        board.frame = session->CurrentFrame();
        board.confirmed = session->ConfirmedFrame();
        board.rollbacks = s.rollbacks;
        board.resimulated = s.framesResimulated;
        board.deepest = s.deepestRollback;
        board.inputDelay = session->InputDelay();
        {
            std::lock_guard<std::mutex> guard(board.lock);
            for (const auto& [f, h] : session->FinalHashes()) board.finals[f] = h;
        }
        for (const net::RollbackEvent& e : session->TakeEvents())
            if (e.kind == net::RollbackEvent::Kind::e_desync) board.desync = true;
        if (session->ConfirmedFrame() >= o.frames) --lingerTicks;
        next += tick;
        std::this_thread::sleep_until(next);
    }
    board.done = true;
}

}  // namespace

int RunRollbackMatch(const RollbackOptions& o) {
    if (o.frames < 1 || o.frames > 1000000 || o.inputDelay < 0 || o.inputDelay > 16 || o.window < 1 || o.window > 64 ||
        o.latencyMs < 0 || o.latencyMs > 1000 || o.budgetMs < 0 || o.budgetMs > 1000) {
        std::fprintf(stderr,
                     "rollback: frames 1..1000000, delay 0..16, window 1..64, latency 0..1000 ms, budget 0..1000 ms\n");
        return 2;
    }
    if (!replay::SceneGame(o.scene).ok()) {
        std::fprintf(stderr, "rollback: unknown scene %s\n", o.scene.c_str());
        return 2;
    }
    std::string error;
    auto a = net::UdpTransport::Open("127.0.0.1", 0, &error);
    auto b = a ? net::UdpTransport::Open("127.0.0.1", 0, &error) : nullptr;
    if (!a || !b) {
        std::fprintf(stderr, "rollback: cannot open a socket: %s\n", error.c_str());
        return 1;
    }
    const net::PeerId aToB = a->AddPeer("127.0.0.1", b->LocalPort(), &error);
    const net::PeerId bToA = b->AddPeer("127.0.0.1", a->LocalPort(), &error);
    if (aToB == net::kNoPeer || bToA == net::kNoPeer) {
        std::fprintf(stderr, "rollback: %s\n", error.c_str());
        return 1;
    }
    std::printf("rollback match: scene %s, %d frames, input delay %d, window %d, one-way latency %d ms (loopback UDP)",
                o.scene.c_str(), o.frames, o.inputDelay, o.window, o.latencyMs);
    if (o.budgetMs > 0) std::printf(", budget guard %d ms", o.budgetMs);
    std::printf("\n");
    const auto start = Clock::now();
    // Three times real time plus slack: the match always ends.
    const auto deadline = start + std::chrono::milliseconds(int64_t{o.frames} * 50 + 15000);
    Board boards[2];
    std::thread ta(PlayerThread, 0u, std::move(a), aToB, o, std::ref(boards[0]), deadline);
    std::thread tb(PlayerThread, 1u, std::move(b), bToA, o, std::ref(boards[1]), deadline);
    uint64_t lastRollbacks[2] = {0, 0};
    auto nextPrint = start + std::chrono::seconds(1);
    while (!(boards[0].done && boards[1].done)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (Clock::now() < nextPrint) continue;
        nextPrint += std::chrono::seconds(1);
        for (int i = 0; i < 2; ++i) {
            const Board& bd = boards[i];
            const uint64_t rb = bd.rollbacks;
            const uint64_t resim = bd.rollbackSteps;
            std::printf(
                "  player %d: frame %5d confirmed %5d  rollbacks/s %3llu  deepest %u  resim %.3f ms/frame  delay %u\n",
                i, bd.frame.load(), bd.confirmed.load(), static_cast<unsigned long long>(rb - lastRollbacks[i]),
                bd.deepest.load(), resim ? static_cast<double>(bd.resimNanos) / 1e6 / static_cast<double>(resim) : 0.0,
                bd.inputDelay.load());
            lastRollbacks[i] = rb;
        }
        std::fflush(stdout);
    }
    ta.join();
    tb.join();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    // Compare every frame both players finalized; the agreed hash is the newest common one.
    int32_t compared = 0, agreedFrame = -1;
    uint64_t agreed = 0;
    bool mismatch = false;
    for (const auto& [f, h] : boards[0].finals) {
        auto it = boards[1].finals.find(f);
        if (it == boards[1].finals.end()) continue;
        ++compared;
        if (it->second != h) mismatch = true;
        agreedFrame = f;
        agreed = h;
    }
    bool ok = !mismatch && compared > 0;
    for (int i = 0; i < 2; ++i) {
        const Board& bd = boards[i];
        const uint64_t resim = bd.rollbackSteps;
        std::printf(
            "player %d: %d frames in %.1f s, %llu rollbacks (%.1f/s), deepest %u, %llu frames resimulated, "
            "resim %.3f ms/frame, input delay %u at the end%s%s\n",
            i, bd.frame.load(), seconds, static_cast<unsigned long long>(bd.rollbacks.load()),
            static_cast<double>(bd.rollbacks) / seconds, bd.deepest.load(),
            static_cast<unsigned long long>(bd.resimulated.load()),
            resim ? static_cast<double>(bd.resimNanos) / 1e6 / static_cast<double>(resim) : 0.0, bd.inputDelay.load(),
            bd.failed ? ", RESTORE FAILED" : "", bd.desync ? ", DESYNC" : "");
        ok = ok && !bd.failed && !bd.desync && bd.confirmed >= o.frames;
    }
    if (ok)
        std::printf("agreed hash %016llx at frame %d (%d frames compared)\n", static_cast<unsigned long long>(agreed),
                    agreedFrame, compared);
    else
        std::printf("players did NOT agree (%d frames compared%s)\n", compared, mismatch ? ", mismatch" : "");
    return ok ? 0 : 1;
}

}  // namespace lockbox::demo
