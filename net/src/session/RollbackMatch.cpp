// RollbackMatch: the per-tick order and the end of a match (RollbackMatch.h).
#include "lockbox/net/RollbackMatch.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>
#include <utility>

#include "lockbox/net/StateHash.h"
#include "lockbox/net/UdpTransport.h"

namespace lockbox::net {

namespace {
// Flushes after this peer's own hash of the last frame became final before it leaves: the
// peer sends each final hash in this many datagrams, so a remote that still waits for it
// hears it unless all of them are lost (it then sees this peer leave instead).
constexpr uint32_t kHashFlushes = 3;
}  // namespace

const char* MatchPhaseName(MatchPhase phase) noexcept {
    switch (phase) {
        case MatchPhase::e_synchronizing: return "synchronizing";
        case MatchPhase::e_running: return "running";
        case MatchPhase::e_ending: return "ending";
        case MatchPhase::e_ended: return "ended";
        case MatchPhase::e_failed: return "failed";
    }
    return "unknown";
}

bool RollbackMatchEnd::Agreed() const noexcept {
    if (!finished) return false;
    for (const RollbackRemoteEnd& r : remotes)
        if (r.desynced || (r.hashed && r.hash != hash)) return false;
    return true;
}

RollbackMatch::~RollbackMatch() = default;

uint64_t RollbackMatch::TickMicros() const noexcept { return 1000000u / m_tickRate; }

uint64_t RollbackMatch::StateHash() const { return FoldedStateHash(*m_world, *m_game); }

std::vector<RollbackEvent> RollbackMatch::TakeEvents() {
    std::vector<RollbackEvent> out;
    out.swap(m_events);
    return out;
}

void RollbackMatch::Leave() {
    if (m_end.ended) return;
    m_peer->Leave();
    m_end.ended = true;
    m_phase = MatchPhase::e_ended;
}

void RollbackMatch::Fail(std::string why) {
    if (m_end.ended) return;
    m_peer->Leave();
    m_end.ended = true;
    m_end.failed = true;
    m_end.failure = std::move(why);
    m_phase = MatchPhase::e_failed;
}

bool RollbackMatch::EndAt(int32_t frame, uint64_t timeoutMicros) {
    const uint32_t interval = m_session->Config().desyncInterval;
    if (frame < 0 || interval == 0 || frame % static_cast<int32_t>(interval) != 0 || m_end.ended) return false;
    for (uint32_t p : m_local)
        if (m_session->ReceivedFrame(p) > frame) return false;
    m_endFrame = frame;
    m_endTimeout = timeoutMicros;
    m_end.frame = frame;
    return true;
}

MatchPhase RollbackMatch::Tick(const MatchInputSource& inputs) {
    if (m_end.ended) return m_phase;
    m_peer->Poll();
    // Time sync may ask the peer that runs ahead to sit a tick out; never once frame N is
    // reached, when only the remaining rollbacks and the other peers' hashes matter.
    const bool skip = m_phase == MatchPhase::e_running && m_peer->WaitThisTick();
    if (!skip) {
        for (uint32_t p : m_local) {
            const int32_t frame = m_session->ReceivedFrame(p);
            if (m_endFrame >= 0 && frame >= m_endFrame) continue;
            std::fill(m_input.begin(), m_input.end(), uint8_t{0});
            if (inputs) inputs(p, frame, m_input);
            // e_alreadyAdded: the session waits with an input queued; this frame's input is
            // asked for again next tick.
            m_session->AddLocalInput(p, m_input);
        }
        const std::vector<RollbackRequest> requests = m_session->AdvanceFrame();
        if (!m_adapter->Execute(*m_session, requests)) {
            Fail("a rollback asked for a state the adapter no longer keeps");
            return m_phase;
        }
    }
    m_peer->Flush();
    std::string missing;
    for (RollbackEvent& e : m_session->TakeEvents()) {
        using K = RollbackEvent::Kind;
        if (e.kind == K::e_desync && e.player < m_end.remotes.size()) m_end.remotes[e.player].desynced = true;
        if (e.kind == K::e_startTimeout && e.player < m_remoteNames.size())
            missing += (missing.empty() ? "" : ", ") + m_remoteNames[e.player];
        if (e.kind == K::e_removed) Fail("the other peers removed this one from the match");
        m_events.push_back(e);
    }
    if (m_peer->State() == RollbackPeerState::e_startFailed) Fail("start timeout: never heard " + missing);
    if (m_end.ended) return m_phase;
    if (m_phase == MatchPhase::e_synchronizing && m_peer->State() == RollbackPeerState::e_running)
        m_phase = MatchPhase::e_running;
    CheckEnd();
    return m_phase;
}

void RollbackMatch::CheckEnd() {
    if (m_endFrame < 0 || m_phase == MatchPhase::e_synchronizing) return;
    const int32_t last = m_endFrame;
    const uint64_t now = m_net->NowMicros();
    if (!m_reached && m_session->CurrentFrame() >= last) {
        m_reached = true;
        m_phase = MatchPhase::e_ending;
        m_endDeadline = now + m_endTimeout < now ? UINT64_MAX : now + m_endTimeout;
    }
    if (!m_reached) return;
    // Final here means every live peer holds every input before `last`; the requests of this
    // tick applied any rollback those inputs caused, so the world is at `last` for good.
    if (!m_hashed && m_session->ConfirmedFrame() >= last && m_session->CurrentFrame() == last) {
        m_end.hash = StateHash();
        m_hashed = true;
    }
    if (m_hashed) {
        const auto& finals = m_session->FinalHashes();
        if (!finals.empty() && finals.back().first >= last) ++m_flushesAfterHash;
        bool all = true;
        for (size_t i = 0; i < m_end.remotes.size(); ++i) {
            RollbackRemoteEnd& r = m_end.remotes[i];
            const RollbackRemoteStats s = m_peer->RemoteStats(i);
            r.hashed = s.finalHashFrame >= last;
            if (s.finalHashFrame == last) r.hash = s.finalHash;
            r.left = !r.hashed && !s.alive;
            if (!r.hashed && !r.left) all = false;
        }
        if (all && m_flushesAfterHash >= kHashFlushes) {
            m_end.finished = true;
            Leave();
            return;
        }
    }
    if (now >= m_endDeadline) {
        m_end.timedOut = true;
        Leave();
    }
}

RollbackMatchEnd RollbackMatch::PlayTo(int32_t frame, const MatchInputSource& inputs, uint64_t timeoutMicros) {
    if (!EndAt(frame, timeoutMicros)) {
        RollbackMatchEnd refused = m_end;
        refused.failed = true;
        refused.failure = "cannot end at frame " + std::to_string(frame) +
                          ": it must be a multiple of the desync interval (on) and not behind the local inputs";
        return refused;
    }
    using Clock = std::chrono::steady_clock;
    const auto tick = std::chrono::microseconds(TickMicros());
    auto next = Clock::now();
    while (!m_end.ended) {
        Tick(inputs);
        next += tick;
        const auto now = Clock::now();
        // After a stall (a slow machine, a debugger) start the beat again rather than catch up.
        if (next < now - tick) next = now;
        std::this_thread::sleep_until(next);
    }
    return m_end;
}

}  // namespace lockbox::net
