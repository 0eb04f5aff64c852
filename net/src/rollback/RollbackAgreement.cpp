// RollbackPeer's side of the disconnect agreement (RollbackPeer.h, docs/rollback.md
// "Disconnects"): views out and in, remotes that stop counting as live, frozen values
// announced and gossiped, and the cut once every live remote's frozen value is known.
//
// Why it agrees: every survivor cuts a leaving player at the smallest frozen value among
// its own and those it heard, and waits until every peer it still counts as live has
// announced one. Survivors that count the same peers as live and heard the same values get
// the same minimum; the session keeps every final frame below every frozen value, so the cut
// never changes a frame any survivor already compared or streamed.

#include <algorithm>
#include <vector>

#include "rollback/RollbackPeerRemote.h"

namespace lockbox::net {

void RollbackPeer::DropRemote(Remote& r, bool tell) {
    if (!r.alive) return;
    r.alive = false;
    r.interrupted = false;
    m_session.DropPeer(r.index);
    // Freeze at what this peer holds now; the agreement may lower it to a survivor's value.
    for (uint32_t p : r.players) m_session.FreezePlayer(p);
    if (tell && !m_left) {
        // It may still run (a half-broken link, a long stall): a few copies of its players'
        // frozen values tell it it is out (e_removed there) instead of letting it play on alone.
        m_writer.Begin(RollbackHeader{kRollbackProtocolVersion, m_config.matchId});
        for (uint32_t p : r.players)
            if (m_session.FrozenFrame(p) >= 0)
                m_writer.Add(RbFrozen{static_cast<uint8_t>(p), m_session.FrozenFrame(p)}, m_shape,
                             m_transport.MaxDatagram());
        for (int copy = 0; copy < 3 && m_writer.MessageCount() > 0; ++copy)
            if (m_transport.Send(r.peer, m_writer.Bytes())) ++m_stats.datagramsSent;
    }
    // One peer fewer to wait for: agreements pending on its value may complete now.
    TryAgree();
}

void RollbackPeer::OnView(Remote& r, const RbView& v) {
    if (v.received.size() != m_shape.players) return;
    m_session.SetPeerView(r.index, v.received);
    for (uint32_t lp : m_localPlayers) {
        // An ack never runs past what this peer has: a confused remote cannot make us skip
        // inputs it never got.
        const int32_t known = std::min(v.received[lp], m_session.ReceivedFrame(lp));
        r.acked[lp] = std::max(r.acked[lp], known);
    }
}

void RollbackPeer::OnFrozen(Remote& r, const RbFrozen& f) {
    const uint32_t p = f.player;
    if (p >= m_shape.players) return;
    if (m_session.IsLocal(p)) {
        // This peer is named gone: the others no longer count it. Nothing here can undo
        // that (it will stop hearing them and time them out), but the game learns it now.
        if (!m_removed[p]) {
            m_removed[p] = true;
            m_session.RaiseRemoved(p, f.frame);
        }
        return;
    }
    if (std::find(r.players.begin(), r.players.end(), p) != r.players.end()) return;  // about itself
    if (m_session.CutFrame(p) >= 0) return;                                           // settled here already
    // Gossip: one live peer calling p gone is enough, even while p is still heard here (a
    // half-broken link); p's owner then stops counting as live for this peer too.
    for (Remote& owner : m_remotes)
        if (std::find(owner.players.begin(), owner.players.end(), p) != owner.players.end()) DropRemote(owner);
    m_session.FreezePlayer(p);
    if (m_session.CutFrame(p) >= 0) return;  // DropRemote completed it (no one left to wait for)
    // A remote's frozen value never changes; the first one heard is the one.
    if (r.frozenHeard[p] < 0) {
        r.frozenHeard[p] = f.frame;
        m_session.ReportFrozen(p, f.frame);
    }
    TryAgree();
}

void RollbackPeer::TryAgree() {
    for (uint32_t p = 0; p < m_shape.players; ++p) {
        if (m_session.FrozenFrame(p) < 0 || m_session.CutFrame(p) >= 0) continue;
        bool all = true;
        for (const Remote& r : m_remotes)
            if (r.alive && r.frozenHeard[p] < 0) all = false;
        if (all) m_session.CompleteDisconnect(p);
    }
}

void RollbackPeer::AddAgreement(size_t limit) {
    RbView view;
    view.received.resize(m_shape.players);
    for (uint32_t p = 0; p < m_shape.players; ++p) view.received[p] = m_session.ReceivedFrame(p);
    m_writer.Add(view, m_shape, limit);
    // Every frozen value, every datagram, for the rest of the match: datagrams get lost, and
    // a peer that has not heard it cannot complete its cut.
    for (uint32_t p = 0; p < m_shape.players; ++p) {
        const int32_t frozen = m_session.FrozenFrame(p);
        if (frozen >= 0) m_writer.Add(RbFrozen{static_cast<uint8_t>(p), frozen}, m_shape, limit);
    }
}

}  // namespace lockbox::net
