// RollbackPeer's spectator side (RollbackPeer.h): the confirmed input stream, and the late
// join: a spectator's RbJoinRequest marks it as waiting, the game offers the bytes of a final
// frame, and the snapshot goes out in acked, resent chunks before the stream resumes there.

#include "rollback/RollbackSnapshotHost.h"

#include <xxhash.h>

#include <algorithm>

namespace lockbox::net {

namespace {

// Raw input bytes of one spectator run, so a datagram stays under the 1200-byte limit (and
// under a relayed transport's 1,191).
constexpr size_t kSpectatorRunBytes = 960;

}  // namespace

RollbackPeer::Spectator* RollbackPeer::FindSpectator(PeerId peer) {
    for (Spectator& s : m_spectators)
        if (s.peer == peer) return &s;
    return nullptr;
}

void RollbackPeer::HandleSpectator(Spectator& s, const RollbackMessage& m, uint64_t now) {
    if (const auto* ack = std::get_if<RbConfirmedAck>(&m)) {
        s.acked = std::max(s.acked, std::min(ack->nextFrame, m_session.ConfirmedFrame()));
    } else if (const auto* join = std::get_if<RbJoinRequest>(&m)) {
        // Each new attempt (the spectator refused the last snapshot) gets a fresh snapshot;
        // repeats of the same attempt are the spectator resending its request.
        if (join->attempt <= s.attempt) return;
        s.attempt = join->attempt;
        s.lateJoin = true;
        s.wantsSnapshot = true;
        s.sender.Stop();
    } else if (const auto* sack = std::get_if<RbSnapshotAck>(&m)) {
        s.sender.OnAck(SnapshotAck{sack->frame, sack->index}, now);
    }
}

bool RollbackPeer::SnapshotWanted() const noexcept {
    return std::any_of(m_spectators.begin(), m_spectators.end(), [](const Spectator& s) { return s.wantsSnapshot; });
}

size_t RollbackPeer::SpectatorCount() const noexcept { return m_spectators.size(); }

bool RollbackPeer::InputsKept(int32_t frame) const {
    for (uint32_t p = 0; p < m_shape.players; ++p) {
        if (frame >= m_session.ReceivedFrame(p)) continue;  // not arrived yet: comes in order later
        if (m_session.ConfirmedInput(p, frame).size() != m_shape.inputBytes) return false;
    }
    return true;
}

SnapshotOfferResult RollbackPeer::OfferSnapshot(int32_t frame, std::span<const uint8_t> state) {
    if (!SnapshotWanted()) return SnapshotOfferResult::e_notWanted;
    if (frame < 0 || frame > std::min(m_session.ConfirmedFrame(), m_session.CurrentFrame()))
        return SnapshotOfferResult::e_notConfirmed;
    if (state.empty() || state.size() > kRbMaxSnapshotBytes) return SnapshotOfferResult::e_badSize;
    if (!InputsKept(frame)) return SnapshotOfferResult::e_inputsGone;
    const uint64_t checksum = XXH3_64bits(state.data(), state.size());
    // Compressed once for every spectator that waits for it.
    const CompressedSnapshot compressed = SnapshotSender::Compress(state);
    for (Spectator& s : m_spectators) {
        if (!s.wantsSnapshot) continue;
        s.wantsSnapshot = false;
        s.checksum = checksum;
        s.acked = frame;
        s.sender.Start(frame, compressed);
    }
    ++m_stats.snapshotsOffered;
    return SnapshotOfferResult::e_ok;
}

void RollbackPeer::SendSnapshot(Spectator& s, uint64_t now) {
    const size_t limit = m_transport.MaxDatagram();  // a relay takes its header from it
    size_t sent = 0;
    if (s.sender.Active()) {
        static_assert(kSnapshotChunkBytes == kRbSnapshotChunkBytes, "SnapshotSender chunks must match the wire");
        RbSnapshotChunk chunk;
        sent = s.sender.Pump(
            now, m_config.snapshotResendMicros, m_config.snapshotChunksPerFlush, [&](const SnapshotChunk& c) {
                chunk.frame = c.frame;
                chunk.totalSize = c.totalSize;
                chunk.checksum = s.checksum;
                chunk.index = c.index;
                chunk.bytes = c.bytes;
                m_writer.Begin(RollbackHeader{kRollbackProtocolVersion, m_config.matchId});
                if (m_writer.Add(chunk, m_shape, limit) && m_transport.Send(s.peer, m_writer.Bytes())) {
                    ++m_stats.datagramsSent;
                    ++m_stats.snapshotChunksSent;
                }
            });
    }
    if (sent > 0) return;
    // Waiting for the game's offer or for acks: the spectator still hears from its host (and
    // its hello, which the full chunk datagrams have no room for).
    BeginDatagram(true, limit);
    m_writer.Add(RbKeepAlive{}, m_shape, limit);
    if (m_transport.Send(s.peer, m_writer.Bytes())) ++m_stats.datagramsSent;
}

void RollbackPeer::SendSpectator(Spectator& s) {
    const size_t limit = m_transport.MaxDatagram();  // a relay takes its header from it
    BeginDatagram(true, limit);
    const size_t width = m_shape.inputBytes;
    const size_t row = width * m_shape.players;
    const int32_t confirmed = m_session.ConfirmedFrame();
    const int32_t maxRun = static_cast<int32_t>(std::min<size_t>(kRollbackMaxRun, kSpectatorRunBytes / row));
    RbConfirmed c;
    c.firstFrame = s.acked;
    int32_t count = 0;
    for (int32_t f = s.acked; f < confirmed && count < maxRun; ++f, ++count) {
        bool kept = true;
        for (uint32_t p = 0; p < m_shape.players && kept; ++p) {
            const auto one = m_session.ConfirmedInput(p, f);
            if (one.size() == width) {
                c.bytes.insert(c.bytes.end(), one.begin(), one.end());
            } else if (m_session.IsDisconnected(p) && f >= m_session.ReceivedFrame(p)) {
                c.bytes.insert(c.bytes.end(), width, 0);
            } else {
                kept = false;
            }
        }
        if (!kept) {
            c.bytes.resize(static_cast<size_t>(count) * row);
            break;
        }
    }
    if (count > 0) {
        m_writer.Add(c, m_shape, limit);
    } else {
        // A late joiner whose next frame's inputs the session dropped (it took too long to
        // fetch its snapshot) can never catch up from here: it needs a newer snapshot.
        if (s.lateJoin && s.acked < confirmed && !InputsKept(s.acked)) s.wantsSnapshot = true;
        m_writer.Add(RbKeepAlive{}, m_shape, limit);
    }
    if (m_transport.Send(s.peer, m_writer.Bytes())) ++m_stats.datagramsSent;
}

}  // namespace lockbox::net
