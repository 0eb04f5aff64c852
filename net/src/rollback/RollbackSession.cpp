// The rollback session core: input rings, prediction, the request stream, and final-hash
// bookkeeping. See RollbackSession.h for the contract; finality, views and disconnect cuts
// are in RollbackSessionFinality.cpp.

#include "rollback/RollbackSessionImpl.h"

namespace lockbox::net {

using rbsession::kFinalKept;
using rbsession::kFinalOffered;
using rbsession::kInputRing;
using rbsession::kRemotePendingMax;
using rbsession::Slot;

std::string_view RollbackSessionBuilder::Check() const noexcept {
    const RollbackConfig& c = m_config;
    if (c.players < 1 || c.players > kRollbackMaxPlayers) return "players must be in 1..8";
    if (c.inputBytes < 1 || c.inputBytes > kRollbackMaxInputBytes) return "input bytes must be in 1..64";
    if (c.predictionWindow < 1 || c.predictionWindow > kRollbackMaxWindow) return "prediction window must be in 1..64";
    if (c.inputDelay > kRollbackMaxInputDelay) return "input delay must be in 0..16";
    if (c.checkDistance < 1 || c.checkDistance > kRollbackMaxWindow) return "check distance must be in 1..64";
    for (size_t i = 0; i < c.localPlayers.size(); ++i) {
        if (c.localPlayers[i] >= c.players) return "a local player is not a player";
        for (size_t j = 0; j < i; ++j)
            if (c.localPlayers[j] == c.localPlayers[i]) return "a local player is listed twice";
    }
    return {};
}

std::unique_ptr<RollbackSession> RollbackSessionBuilder::Build() const {
    if (!Check().empty()) return nullptr;
    return std::make_unique<RollbackSession>(m_config);
}

InputStatus RollbackSession::Impl::InputFor(uint32_t index, int32_t frame, uint8_t* out) {
    Player& p = players[index];
    if (p.disconnected && frame >= p.disconnectFrame) {
        std::memset(out, 0, Bytes());
        return InputStatus::e_disconnected;
    }
    if (frame < p.received) {
        std::memcpy(out, InputAt(p, frame), Bytes());
        return InputStatus::e_confirmed;
    }
    scratch.assign(Bytes(), 0);
    const int32_t lastFrame = p.received - 1;
    if (lastFrame >= 0) std::memcpy(scratch.data(), InputAt(p, lastFrame), Bytes());
    std::memcpy(out, scratch.data(), Bytes());
    if (config.predictor) config.predictor(index, frame, scratch, lastFrame, std::span<uint8_t>(out, Bytes()));
    return InputStatus::e_predicted;
}

void RollbackSession::Impl::EmitAdvance(std::vector<RollbackRequest>& out, int32_t frame, bool fresh) {
    AdvanceRequest a;
    a.frame = frame;
    a.inputs.resize(RowBytes());
    a.status.resize(config.players);
    for (uint32_t i = 0; i < config.players; ++i) {
        a.status[i] = InputFor(i, frame, a.inputs.data() + i * Bytes());
        if (fresh && a.status[i] == InputStatus::e_predicted) ++stats.predictedInputs;
    }
    const int32_t slot = Slot(frame, kInputRing);
    std::memcpy(used.data() + static_cast<size_t>(slot) * RowBytes(), a.inputs.data(), RowBytes());
    usedFrame[static_cast<size_t>(slot)] = frame;
    out.emplace_back(std::move(a));
}

void RollbackSession::Impl::EmitSave(std::vector<RollbackRequest>& out, int32_t frame) {
    SaveSlot& s = saves[static_cast<size_t>(Slot(frame, static_cast<int32_t>(saves.size())))];
    s = SaveSlot{frame, false, 0};
    const bool want = config.desyncInterval > 0 && frame % static_cast<int32_t>(config.desyncInterval) == 0;
    out.emplace_back(SaveState{frame, want});
}

bool RollbackSession::Impl::CheckPast(uint32_t player, int32_t frame, const uint8_t* actual) {
    if (frame >= current) return false;
    const int32_t slot = Slot(frame, kInputRing);
    if (usedFrame[static_cast<size_t>(slot)] != frame) return false;
    const uint8_t* was = used.data() + static_cast<size_t>(slot) * RowBytes() + player * Bytes();
    if (std::memcmp(was, actual, Bytes()) == 0) return false;
    firstIncorrect = std::min(firstIncorrect, frame);
    return true;
}

void RollbackSession::Impl::Compare(uint32_t peer, int32_t frame, uint64_t local, uint64_t remote) {
    ++stats.hashesCompared;
    if (local == remote) return;
    if (std::find(desyncedPeers.begin(), desyncedPeers.end(), peer) != desyncedPeers.end()) return;
    desyncedPeers.push_back(peer);
    RollbackEvent e;
    e.kind = RollbackEvent::Kind::e_desync;
    e.frame = frame;
    e.player = peer;
    e.localHash = local;
    e.remoteHash = remote;
    events.push_back(e);
}

void RollbackSession::Impl::FinalizeHashes() {
    if (config.desyncInterval == 0) return;
    const int32_t limit = std::min({Final(), firstIncorrect, current});
    const int32_t interval = static_cast<int32_t>(config.desyncInterval);
    int32_t f = nextFinal;
    if (f % interval != 0) f += interval - f % interval;
    for (; f <= limit; f += interval) {
        const SaveSlot& s = saves[static_cast<size_t>(Slot(f, static_cast<int32_t>(saves.size())))];
        if (s.frame != f || !s.hasHash) continue;
        finals[f] = s.hash;
        while (finals.size() > kFinalKept) finals.erase(finals.begin());
        offered.emplace_back(f, s.hash);
        while (offered.size() > kFinalOffered) offered.pop_front();
        for (auto it = remotePending.lower_bound({f, 0}); it != remotePending.end() && it->first.first == f;) {
            Compare(it->first.second, f, s.hash, it->second);
            it = remotePending.erase(it);
        }
    }
    nextFinal = std::max(nextFinal, limit + 1);
}

RollbackSession::RollbackSession(RollbackConfig config) : m_impl(std::make_unique<Impl>()) {
    Impl& m = *m_impl;
    m.config = std::move(config);
    m.players.resize(m.config.players);
    for (Impl::Player& p : m.players) {
        p.ring.assign(static_cast<size_t>(kInputRing) * m.Bytes(), 0);
        p.ringFrame.assign(kInputRing, -1);
    }
    m.used.assign(static_cast<size_t>(kInputRing) * m.RowBytes(), 0);
    m.usedFrame.assign(kInputRing, -1);
    m.saves.resize(static_cast<size_t>(rbsession::kSaveSlots));
    const std::vector<uint8_t> zero(m.Bytes(), 0);
    for (uint32_t lp : m.config.localPlayers) {
        Impl::Player& p = m.players[lp];
        p.local = true;
        // The first inputDelay frames of a local player are empty: its first input lands
        // inputDelay frames after the frame it was added in.
        for (uint32_t f = 0; f < m.config.inputDelay; ++f) m.Store(p, static_cast<int32_t>(f), zero);
    }
}

RollbackSession::~RollbackSession() = default;

InputResult RollbackSession::AddLocalInput(uint32_t player, std::span<const uint8_t> input) {
    Impl& m = *m_impl;
    if (player >= m.config.players || !m.players[player].local) return InputResult::e_badPlayer;
    if (input.size() != m.Bytes()) return InputResult::e_badSize;
    Impl::Player& p = m.players[player];
    if (p.disconnected || p.frozen) return InputResult::e_disconnected;
    int32_t target = m.current + static_cast<int32_t>(m.config.inputDelay) + p.surplus;
    // A queue that ran short (ticks without an input) has already given back what it owed.
    if (p.received < target && p.surplus > 0) {
        const int32_t paid = std::min(p.surplus, target - p.received);
        p.surplus -= paid;
        target -= paid;
    }
    if (p.received > target) return InputResult::e_alreadyAdded;
    if (p.surplus > 0 && p.received == target && p.received > 0 && m.IsRepeat(player, p, input)) {
        // The player repeats itself: the queued frame already says this.
        --p.surplus;
        ++m.stats.inputsAbsorbed;
        return InputResult::e_ok;
    }
    m.Store(p, p.received, input);
    return InputResult::e_ok;
}

bool RollbackSession::SetInputDelay(uint32_t frames) {
    Impl& m = *m_impl;
    if (frames > kRollbackMaxInputDelay) return false;
    const int32_t change = static_cast<int32_t>(frames) - static_cast<int32_t>(m.config.inputDelay);
    m.config.inputDelay = frames;
    if (change == 0) return true;
    std::vector<uint8_t> repeat(m.Bytes(), 0);
    for (Impl::Player& p : m.players) {
        if (!p.local || p.disconnected || p.frozen) continue;
        if (change < 0) {
            p.surplus += -change;
            continue;
        }
        // A raise first cancels what a lowering still owed, then repeats the latest input
        // into the frames that open, so the queue stays contiguous for the peers.
        const int32_t cancelled = std::min(p.surplus, change);
        p.surplus -= cancelled;
        if (p.received > 0) std::memcpy(repeat.data(), m.InputAt(p, p.received - 1), m.Bytes());
        for (int32_t k = cancelled; k < change; ++k) {
            m.Store(p, p.received, repeat);
            ++m.stats.inputsRepeated;
        }
    }
    return true;
}

uint32_t RollbackSession::InputDelay() const noexcept { return m_impl->config.inputDelay; }

std::vector<RollbackRequest> RollbackSession::AdvanceFrame() {
    Impl& m = *m_impl;
    std::vector<RollbackRequest> out;
    if (!m.started) {
        m.started = true;
        m.EmitSave(out, 0);
    }
    // Before the start nothing is simulated, so nothing can be final or rolled back either.
    if (m.synchronizing) return out;
    // The game executed the previous call's requests, so every reported hash belongs to the
    // latest save of its frame; only now may hashes become final.
    m.FinalizeHashes();
    if (m.firstIncorrect < m.current) {
        const int32_t from = m.firstIncorrect;
        out.emplace_back(LoadState{from});
        for (int32_t f = from; f < m.current; ++f) {
            m.EmitAdvance(out, f, false);
            m.EmitSave(out, f + 1);
        }
        ++m.stats.rollbacks;
        const uint32_t depth = static_cast<uint32_t>(m.current - from);
        m.stats.framesResimulated += depth;
        m.stats.deepestRollback = std::max(m.stats.deepestRollback, depth);
    }
    m.firstIncorrect = INT32_MAX;

    bool localReady = true;
    for (const Impl::Player& p : m.players)
        if (p.local && !p.disconnected && p.received <= m.current) localReady = false;
    // The window counts inputs this session holds. The final frame may trail further (it
    // waits for the peers' views); past kRollbackMaxFinalLag the session waits too, so a
    // disconnect cut never asks for a state older than the game keeps.
    const bool windowFull = m.current - m.Held() >= static_cast<int32_t>(m.config.predictionWindow) ||
                            m.current - m.Final() >= static_cast<int32_t>(kRollbackMaxFinalLag);
    if (!localReady || windowFull) {
        ++m.stats.waits;
        if (windowFull && !m.stalled) {
            RollbackEvent e;
            e.kind = RollbackEvent::Kind::e_waiting;
            e.frame = m.current;
            m.events.push_back(e);
        }
        m.stalled = windowFull;
        return out;
    }
    m.stalled = false;
    m.EmitAdvance(out, m.current, true);
    ++m.current;
    ++m.stats.framesAdvanced;
    m.EmitSave(out, m.current);
    return out;
}

void RollbackSession::ReportHash(int32_t frame, uint64_t hash) {
    Impl& m = *m_impl;
    if (frame < 0) return;
    Impl::SaveSlot& s = m.saves[static_cast<size_t>(Slot(frame, static_cast<int32_t>(m.saves.size())))];
    if (s.frame != frame) return;
    s.hash = hash;
    s.hasHash = true;
}

InputResult RollbackSession::AddRemoteInput(uint32_t player, int32_t frame, std::span<const uint8_t> input) {
    Impl& m = *m_impl;
    if (player >= m.config.players || m.players[player].local) return InputResult::e_badPlayer;
    if (input.size() != m.Bytes()) return InputResult::e_badSize;
    Impl::Player& p = m.players[player];
    if (p.disconnected || p.frozen) return InputResult::e_disconnected;
    if (frame < p.received) return InputResult::e_duplicate;
    if (frame > p.received) return InputResult::e_gap;
    // The ring must still hold every frame a rollback (or a spectator) may need: from the
    // final frame, or the window's start if that is older.
    const int64_t oldestNeeded =
        std::min<int64_t>(int64_t{m.current} - m.config.predictionWindow - 1, int64_t{m.Final()});
    if (int64_t{frame} - oldestNeeded >= kInputRing) return InputResult::e_tooFarAhead;
    m.Store(p, frame, input);
    if (m.CheckPast(player, frame, input.data())) ++p.mispredicted;
    return InputResult::e_ok;
}

void RollbackSession::AddRemoteHash(uint32_t peerTag, int32_t frame, uint64_t hash) {
    Impl& m = *m_impl;
    if (frame < 0) return;
    if (std::find(m.desyncedPeers.begin(), m.desyncedPeers.end(), peerTag) != m.desyncedPeers.end()) return;
    if (auto it = m.finals.find(frame); it != m.finals.end()) {
        m.Compare(peerTag, frame, it->second, hash);
        return;
    }
    // Older than anything we keep: nothing to compare with.
    if (frame < m.nextFinal) return;
    m.remotePending[{frame, peerTag}] = hash;
    while (m.remotePending.size() > kRemotePendingMax) m.remotePending.erase(std::prev(m.remotePending.end()));
}

void RollbackSession::RaiseConnectionEvent(RollbackEvent::Kind kind, uint32_t peerTag) {
    using K = RollbackEvent::Kind;
    if (kind != K::e_interrupted && kind != K::e_resumed && kind != K::e_synchronizing && kind != K::e_synchronized &&
        kind != K::e_running && kind != K::e_startTimeout)
        return;
    RollbackEvent e;
    e.kind = kind;
    e.frame = m_impl->current;
    e.player = peerTag;
    m_impl->events.push_back(e);
}

void RollbackSession::SetSynchronizing(bool synchronizing) noexcept { m_impl->synchronizing = synchronizing; }
bool RollbackSession::Synchronizing() const noexcept { return m_impl->synchronizing; }

void RollbackSession::RaiseIncompatible(uint32_t peerTag, RollbackIncompatibility why) {
    RollbackEvent e;
    e.kind = RollbackEvent::Kind::e_incompatible;
    e.frame = m_impl->current;
    e.player = peerTag;
    e.incompatibility = why;
    m_impl->events.push_back(e);
}

void RollbackSession::RaiseRemoved(uint32_t player, int32_t frame) {
    RollbackEvent e;
    e.kind = RollbackEvent::Kind::e_removed;
    e.frame = frame;
    e.player = player;
    m_impl->events.push_back(e);
}

int32_t RollbackSession::CurrentFrame() const noexcept { return m_impl->current; }
int32_t RollbackSession::ConfirmedFrame() const noexcept { return m_impl->Final(); }
int32_t RollbackSession::HeldFrame() const noexcept { return m_impl->Held(); }

int32_t RollbackSession::ReceivedFrame(uint32_t player) const noexcept {
    return player < m_impl->config.players ? m_impl->players[player].received : 0;
}

std::span<const uint8_t> RollbackSession::ConfirmedInput(uint32_t player, int32_t frame) const noexcept {
    const Impl& m = *m_impl;
    if (player >= m.config.players || frame < 0) return {};
    const Impl::Player& p = m.players[player];
    if (frame >= p.received || p.ringFrame[static_cast<size_t>(Slot(frame, kInputRing))] != frame) return {};
    return {p.ring.data() + static_cast<size_t>(Slot(frame, kInputRing)) * m.Bytes(), m.Bytes()};
}

const std::deque<std::pair<int32_t, uint64_t>>& RollbackSession::FinalHashes() const noexcept {
    return m_impl->offered;
}
uint64_t RollbackSession::MispredictedInputs(uint32_t player) const noexcept {
    return player < m_impl->config.players ? m_impl->players[player].mispredicted : 0;
}
bool RollbackSession::IsLocal(uint32_t player) const noexcept {
    return player < m_impl->config.players && m_impl->players[player].local;
}
bool RollbackSession::IsDisconnected(uint32_t player) const noexcept {
    return player < m_impl->config.players && m_impl->players[player].disconnected;
}
std::vector<RollbackEvent> RollbackSession::TakeEvents() { return std::exchange(m_impl->events, {}); }
const RollbackStats& RollbackSession::Stats() const noexcept { return m_impl->stats; }
const RollbackConfig& RollbackSession::Config() const noexcept { return m_impl->config; }

}  // namespace lockbox::net
