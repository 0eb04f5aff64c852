// The rollback session core: input rings, prediction, the request stream, and final-hash
// bookkeeping. See RollbackSession.h for the contract.

#include "lockbox/net/RollbackSession.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <map>

namespace lockbox::net {

namespace {

// Frames of inputs kept per player. The worst case a peer can lag behind our newest local
// input is about 2 * (window + delay) frames (docs/rollback.md), far below this.
constexpr int32_t kInputRing = 512;
// Final local hashes kept for comparison with late remote reports.
constexpr size_t kFinalKept = 64;
// Final local hashes offered to the network (FinalHashes()).
constexpr size_t kFinalOffered = 8;
// Remote hashes waiting for our own final hash of the same frame.
constexpr size_t kRemotePendingMax = 256;

int32_t Slot(int32_t frame, int32_t size) noexcept { return frame % size; }

}  // namespace

std::string_view RollbackSessionBuilder::Check() const noexcept {
    const RollbackConfig& c = config_;
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
    return std::make_unique<RollbackSession>(config_);
}

struct RollbackSession::Impl {
    struct Player {
        bool local = false;
        bool disconnected = false;
        int32_t received = 0;          // frames before this are known
        int32_t disconnectFrame = INT32_MAX;
        std::vector<uint8_t> ring;     // kInputRing * inputBytes
        std::vector<int32_t> ringFrame;
    };
    struct SaveSlot {
        int32_t frame = -1;
        bool hasHash = false;
        uint64_t hash = 0;
    };

    RollbackConfig config;
    std::vector<Player> players;
    int32_t current = 0;
    bool started = false;
    bool stalled = false;
    int32_t firstIncorrect = INT32_MAX;
    // What the last Advance of each frame used: one row of players * inputBytes per frame.
    std::vector<uint8_t> used;
    std::vector<int32_t> usedFrame;
    std::vector<SaveSlot> saves;
    int32_t nextFinal = 0;  // frames before this had their final hash decided
    std::deque<std::pair<int32_t, uint64_t>> offered;
    std::map<int32_t, uint64_t> finals;  // frame -> final local hash (ordered: trimmed oldest first)
    std::map<std::pair<int32_t, uint32_t>, uint64_t> remotePending;  // (frame, peer) -> hash
    std::vector<uint32_t> desyncedPeers;
    std::vector<RollbackEvent> events;
    RollbackStats stats;
    std::vector<uint8_t> scratch;

    size_t Bytes() const noexcept { return config.inputBytes; }
    size_t RowBytes() const noexcept { return config.inputBytes * config.players; }

    uint8_t* InputAt(Player& p, int32_t frame) { return p.ring.data() + Slot(frame, kInputRing) * Bytes(); }

    void Store(Player& p, int32_t frame, std::span<const uint8_t> bytes) {
        std::memcpy(InputAt(p, frame), bytes.data(), Bytes());
        p.ringFrame[static_cast<size_t>(Slot(frame, kInputRing))] = frame;
        p.received = frame + 1;
    }

    int32_t Confirmed() const noexcept {
        int32_t c = INT32_MAX;
        for (const Player& p : players)
            if (!p.disconnected) c = std::min(c, p.received);
        // With everyone gone every simulated frame is final.
        return c == INT32_MAX ? current : c;
    }

    // Fills one player's input for `frame` into `out`; returns its status.
    InputStatus InputFor(uint32_t index, int32_t frame, uint8_t* out) {
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
        if (config.predictor) {
            std::span<uint8_t> dst(out, Bytes());
            std::memcpy(out, scratch.data(), Bytes());
            config.predictor(index, frame, scratch, lastFrame, dst);
        } else {
            std::memcpy(out, scratch.data(), Bytes());
        }
        return InputStatus::e_predicted;
    }

    void EmitAdvance(std::vector<RollbackRequest>& out, int32_t frame, bool fresh) {
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

    void EmitSave(std::vector<RollbackRequest>& out, int32_t frame) {
        SaveSlot& s = saves[static_cast<size_t>(Slot(frame, static_cast<int32_t>(saves.size())))];
        s = SaveSlot{frame, false, 0};
        const bool want = config.desyncInterval > 0 && frame % static_cast<int32_t>(config.desyncInterval) == 0;
        out.emplace_back(SaveState{frame, want});
    }

    // Marks `frame` for re-simulation when the input a past Advance used for `player`
    // differs from `actual`.
    void CheckPast(uint32_t player, int32_t frame, const uint8_t* actual) {
        if (frame >= current) return;
        const int32_t slot = Slot(frame, kInputRing);
        if (usedFrame[static_cast<size_t>(slot)] != frame) return;
        const uint8_t* was = used.data() + static_cast<size_t>(slot) * RowBytes() + player * Bytes();
        if (std::memcmp(was, actual, Bytes()) != 0) firstIncorrect = std::min(firstIncorrect, frame);
    }

    void Compare(uint32_t peer, int32_t frame, uint64_t local, uint64_t remote) {
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

    // Hashes of frames whose inputs are all confirmed and that no pending rollback will
    // re-simulate become final; compare them with what the peers reported.
    void FinalizeHashes() {
        if (config.desyncInterval == 0) return;
        const int32_t limit = std::min({Confirmed(), firstIncorrect, current});
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
};

RollbackSession::RollbackSession(RollbackConfig config) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.config = std::move(config);
    m.players.resize(m.config.players);
    for (Impl::Player& p : m.players) {
        p.ring.assign(static_cast<size_t>(kInputRing) * m.Bytes(), 0);
        p.ringFrame.assign(kInputRing, -1);
    }
    m.used.assign(static_cast<size_t>(kInputRing) * m.RowBytes(), 0);
    m.usedFrame.assign(kInputRing, -1);
    m.saves.resize(m.config.predictionWindow + 2);
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
    Impl& m = *impl_;
    if (player >= m.config.players || !m.players[player].local) return InputResult::e_badPlayer;
    if (input.size() != m.Bytes()) return InputResult::e_badSize;
    Impl::Player& p = m.players[player];
    if (p.disconnected) return InputResult::e_disconnected;
    const int32_t target = m.current + static_cast<int32_t>(m.config.inputDelay);
    if (p.received > target) return InputResult::e_alreadyAdded;
    m.Store(p, p.received, input);
    return InputResult::e_ok;
}

std::vector<RollbackRequest> RollbackSession::AdvanceFrame() {
    Impl& m = *impl_;
    std::vector<RollbackRequest> out;
    if (!m.started) {
        m.started = true;
        m.EmitSave(out, 0);
    }
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
    const bool windowFull = m.current - m.Confirmed() >= static_cast<int32_t>(m.config.predictionWindow);
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
    Impl& m = *impl_;
    if (frame < 0) return;
    Impl::SaveSlot& s = m.saves[static_cast<size_t>(Slot(frame, static_cast<int32_t>(m.saves.size())))];
    if (s.frame != frame) return;
    s.hash = hash;
    s.hasHash = true;
}

InputResult RollbackSession::AddRemoteInput(uint32_t player, int32_t frame, std::span<const uint8_t> input) {
    Impl& m = *impl_;
    if (player >= m.config.players || m.players[player].local) return InputResult::e_badPlayer;
    if (input.size() != m.Bytes()) return InputResult::e_badSize;
    Impl::Player& p = m.players[player];
    if (p.disconnected) return InputResult::e_disconnected;
    if (frame < p.received) return InputResult::e_duplicate;
    if (frame > p.received) return InputResult::e_gap;
    // The ring must still hold every frame a rollback may re-simulate.
    const int64_t oldestNeeded = int64_t{m.current} - m.config.predictionWindow - 1;
    if (int64_t{frame} - oldestNeeded >= kInputRing) return InputResult::e_tooFarAhead;
    m.Store(p, frame, input);
    m.CheckPast(player, frame, input.data());
    return InputResult::e_ok;
}

void RollbackSession::AddRemoteHash(uint32_t peerTag, int32_t frame, uint64_t hash) {
    Impl& m = *impl_;
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

void RollbackSession::DisconnectPlayer(uint32_t player) {
    Impl& m = *impl_;
    if (player >= m.config.players) return;
    Impl::Player& p = m.players[player];
    if (p.disconnected) return;
    p.disconnected = true;
    p.disconnectFrame = p.received;
    const std::vector<uint8_t> zero(m.Bytes(), 0);
    for (int32_t f = p.disconnectFrame; f < m.current; ++f) m.CheckPast(player, f, zero.data());
    RollbackEvent e;
    e.kind = RollbackEvent::Kind::e_disconnected;
    e.frame = p.disconnectFrame;
    e.player = player;
    m.events.push_back(e);
}

void RollbackSession::RaiseConnectionEvent(RollbackEvent::Kind kind, uint32_t peerTag) {
    if (kind != RollbackEvent::Kind::e_interrupted && kind != RollbackEvent::Kind::e_resumed) return;
    RollbackEvent e;
    e.kind = kind;
    e.frame = impl_->current;
    e.player = peerTag;
    impl_->events.push_back(e);
}

int32_t RollbackSession::CurrentFrame() const noexcept { return impl_->current; }
int32_t RollbackSession::ConfirmedFrame() const noexcept { return impl_->Confirmed(); }

int32_t RollbackSession::ReceivedFrame(uint32_t player) const noexcept {
    return player < impl_->config.players ? impl_->players[player].received : 0;
}

std::span<const uint8_t> RollbackSession::ConfirmedInput(uint32_t player, int32_t frame) const noexcept {
    const Impl& m = *impl_;
    if (player >= m.config.players || frame < 0) return {};
    const Impl::Player& p = m.players[player];
    if (frame >= p.received || p.ringFrame[static_cast<size_t>(Slot(frame, kInputRing))] != frame) return {};
    return {p.ring.data() + static_cast<size_t>(Slot(frame, kInputRing)) * m.Bytes(), m.Bytes()};
}

const std::deque<std::pair<int32_t, uint64_t>>& RollbackSession::FinalHashes() const noexcept {
    return impl_->offered;
}
bool RollbackSession::IsLocal(uint32_t player) const noexcept {
    return player < impl_->config.players && impl_->players[player].local;
}
bool RollbackSession::IsDisconnected(uint32_t player) const noexcept {
    return player < impl_->config.players && impl_->players[player].disconnected;
}
std::vector<RollbackEvent> RollbackSession::TakeEvents() { return std::exchange(impl_->events, {}); }
const RollbackStats& RollbackSession::Stats() const noexcept { return impl_->stats; }
const RollbackConfig& RollbackSession::Config() const noexcept { return impl_->config; }

}  // namespace lockbox::net
