// RollbackSession's finality and disconnects (RollbackSession.h, docs/rollback.md
// "Disconnects"): what the live remote peers hold (their views), the final frame, and a
// leaving player's freeze and agreed cut.
//
// Why views: with 3+ peers, a leaving player's inputs reach the survivors in different
// amounts, so they must agree on one cut (the smallest frozen frame), and a frame any of
// them calls final must stay the same under that cut. A frame below every live peer's view
// of every player has its inputs on every survivor, so every frozen value, hence the cut, is
// at or past it.

#include "rollback/RollbackSessionImpl.h"

namespace lockbox::net {

int32_t RollbackSession::Impl::Held() const noexcept {
    int32_t held = INT32_MAX;
    for (const Player& p : players)
        if (!p.disconnected) held = std::min(held, p.received);
    // With everyone cut every simulated frame is held.
    return held == INT32_MAX ? current : held;
}

int32_t RollbackSession::Impl::Final() const noexcept {
    int32_t f = Held();
    for (uint32_t i = 0; i < config.players; ++i) {
        const Player& p = players[i];
        // A cut player's inputs are settled on every survivor: below the cut each holds
        // them (the cut is the smallest frozen frame), from it on they are zeros.
        if (p.disconnected) continue;
        for (const auto& [tag, view] : views) f = std::min(f, view[i]);
        // A peer's frozen value may come from a peer that died since: the cut will still
        // include it, so nothing at or past it may become final meanwhile.
        if (p.frozen) f = std::min(f, p.pendingCut);
    }
    return f;
}

void RollbackSession::Impl::Cut(uint32_t index, int32_t cut) {
    Player& p = players[index];
    p.disconnected = true;
    p.disconnectFrame = cut;
    // Inputs from the cut on are zeros for everyone; the real ones this peer received past
    // it are forgotten, so ReceivedFrame, ConfirmedInput and the spectator stream agree.
    if (p.received > cut) p.received = cut;
    const std::vector<uint8_t> zero(Bytes(), 0);
    for (int32_t f = cut; f < current; ++f) CheckPast(index, f, zero.data());
    RollbackEvent e;
    e.kind = RollbackEvent::Kind::e_disconnected;
    e.frame = cut;
    e.player = index;
    events.push_back(e);
}

void RollbackSession::DisconnectPlayer(uint32_t player) {
    if (FreezePlayer(player) < 0) return;
    CompleteDisconnect(player);
}

int32_t RollbackSession::FreezePlayer(uint32_t player) {
    Impl& m = *m_impl;
    if (player >= m.config.players) return -1;
    Impl::Player& p = m.players[player];
    if (p.disconnected) return -1;
    if (!p.frozen) {
        p.frozen = true;
        p.frozenFrame = p.received;
        p.pendingCut = std::min(p.pendingCut, p.received);
    }
    return p.frozenFrame;
}

bool RollbackSession::ReportFrozen(uint32_t player, int32_t frame) {
    Impl& m = *m_impl;
    if (player >= m.config.players || frame < 0) return false;
    Impl::Player& p = m.players[player];
    if (!p.frozen || p.disconnected) return false;
    // Below the final frame the cut would change states already compared and streamed;
    // keeping them is the lesser harm (a peer that uses the value desyncs, and says so).
    if (frame < m.Final()) {
        ++m.stats.frozenReportsIgnored;
        return false;
    }
    p.pendingCut = std::min(p.pendingCut, frame);
    return true;
}

int32_t RollbackSession::CompleteDisconnect(uint32_t player) {
    Impl& m = *m_impl;
    if (player >= m.config.players) return -1;
    Impl::Player& p = m.players[player];
    if (!p.frozen || p.disconnected) return -1;
    const int32_t cut = std::min(p.pendingCut, p.frozenFrame);
    m.Cut(player, cut);
    return cut;
}

void RollbackSession::SetPeerView(uint32_t peerTag, std::span<const int32_t> received) {
    Impl& m = *m_impl;
    if (received.size() != m.config.players) return;
    for (int32_t v : received)
        if (v < 0) return;
    auto [it, fresh] = m.views.try_emplace(peerTag);
    if (fresh) it->second.fill(0);
    for (size_t i = 0; i < received.size(); ++i) it->second[i] = std::max(it->second[i], received[i]);
}

void RollbackSession::DropPeer(uint32_t peerTag) { m_impl->views.erase(peerTag); }

int32_t RollbackSession::FrozenFrame(uint32_t player) const noexcept {
    return player < m_impl->config.players ? m_impl->players[player].frozenFrame : -1;
}

int32_t RollbackSession::CutFrame(uint32_t player) const noexcept {
    if (player >= m_impl->config.players || !m_impl->players[player].disconnected) return -1;
    return m_impl->players[player].disconnectFrame;
}

}  // namespace lockbox::net
