// RollbackSpectator: the confirmed input stream of a rollback match, and the late join from
// a chunked snapshot (RollbackSpectator.h).

#include "lockbox/net/RollbackSpectator.h"

#include <xxhash.h>

#include <algorithm>

#include "lockbox/net/RollbackSession.h"
#include "session/SnapshotTransfer.h"

namespace lockbox::net {

RollbackSpectator::RollbackSpectator(Transport& transport, RollbackSpectatorConfig config)
    : m_transport(transport),
      m_config(config),
      m_receiver(std::make_unique<SnapshotReceiver>(config.maxSnapshotBytes)) {
    m_config.players = std::clamp<uint32_t>(m_config.players, 1, kRollbackMaxPlayers);
    m_config.inputBytes = std::clamp<uint32_t>(m_config.inputBytes, 1, kRollbackMaxInputBytes);
    m_config.maxSnapshotBytes = std::clamp<uint32_t>(m_config.maxSnapshotBytes, 1, kRbMaxSnapshotBytes);
    m_shape = RollbackShape{m_config.players, m_config.inputBytes};
    m_lastHeard = m_transport.NowMicros();
    if (m_config.lateJoin) m_state = SpectatorState::e_joining;
}

RollbackSpectator::~RollbackSpectator() = default;

void RollbackSpectator::TakeChunk(const RbSnapshotChunk& c) {
    static_assert(kSnapshotChunkBytes == kRbSnapshotChunkBytes, "SnapshotReceiver chunks must match the wire");
    if (m_state != SpectatorState::e_joining) {
        // A resend of the accepted snapshot means an ack was lost: ack again, or the host
        // would keep resending and never start the input stream.
        if (m_config.lateJoin && c.frame == m_snapshotFrame && c.checksum == m_snapshotChecksum)
            m_pendingAcks.push_back(RbSnapshotAck{c.frame, c.index});
        return;
    }
    if (c.totalSize > m_config.maxSnapshotBytes) return;
    if (m_hasBad && c.frame == m_badFrame && c.checksum == m_badChecksum) return;
    SnapshotReceiver& r = *m_receiver;
    if (r.Active() && c.frame < r.Frame()) return;  // an older snapshot's straggler
    // Same frame, other bytes: the host restarted its snapshot; assemble the new one.
    if (r.Active() && c.frame == r.Frame() && c.checksum != m_asmChecksum) r.Reset();
    if (!r.Active() || c.frame != r.Frame()) m_asmChecksum = c.checksum;
    const uint32_t before = r.Received();
    if (!r.Accept(SnapshotChunk{c.frame, c.totalSize, c.index, c.bytes})) return;
    m_pendingAcks.push_back(RbSnapshotAck{c.frame, c.index});
    m_snapshotChunks += r.Received() - before;
    if (!r.Complete()) return;
    const std::span<const uint8_t> blob = r.Blob();
    if (r.Failed() || XXH3_64bits(blob.data(), blob.size()) != m_asmChecksum) {
        // Corrupt (or not a zstd frame of at most maxSnapshotBytes): never handed out; ask for a fresh snapshot with a
        // new attempt number.
        ++m_snapshotsRefused;
        m_hasBad = true;
        m_badFrame = r.Frame();
        m_badChecksum = m_asmChecksum;
        ++m_attempt;
        r.Reset();
        return;
    }
    m_snapshotFrame = r.Frame();
    m_snapshotChecksum = m_asmChecksum;
    m_snapshot.assign(blob.begin(), blob.end());
    r.Reset();
    m_snapshotBytes = m_snapshot.size();
    m_received = m_consumed = m_snapshotFrame;
    m_frames.clear();
    m_state = SpectatorState::e_snapshotReady;
}

void RollbackSpectator::Poll() {
    m_inbox.clear();
    m_transport.Poll(m_inbox);
    const uint64_t now = m_transport.NowMicros();
    const size_t row = static_cast<size_t>(m_config.players) * m_config.inputBytes;
    for (const Datagram& d : m_inbox) {
        RollbackHeader header;
        if (d.peer != m_config.host || m_state == SpectatorState::e_incompatible) {
            ++m_refused;
            continue;
        }
        const DecodeError error = DecodeRollbackDatagram(d.bytes, m_shape, header, m_messages);
        const RollbackIncompatibility why =
            FindIncompatibility(error, header, m_messages, m_config.matchId, m_config.determinismVersion);
        if (why != RollbackIncompatibility::e_none) {
            // Frames from a host that simulates differently would only mislead the game.
            m_incompatibility = why;
            m_state = SpectatorState::e_incompatible;
            m_frames.clear();
            m_snapshot.clear();
        }
        if (error != DecodeError::e_ok || why != RollbackIncompatibility::e_none) {  // another match id is a reason
            ++m_refused;
            continue;
        }
        m_lastHeard = now;
        if (!m_hostLeft) {  // a host that said goodbye stays gone; its last datagrams still count
            m_alive = true;
            if (m_interrupted || m_lostReported) m_events.push_back({SpectatorEvent::Kind::e_resumed, m_received});
            m_interrupted = m_lostReported = false;
        }
        for (const RollbackMessage& m : m_messages) {
            if (std::holds_alternative<RbDisconnect>(m)) {
                m_hostLeft = true;
                HostLost();
            }
            if (const auto* chunk = std::get_if<RbSnapshotChunk>(&m)) TakeChunk(*chunk);
            const auto* c = std::get_if<RbConfirmed>(&m);
            // Before its snapshot a late joiner has no frame to continue from.
            if (c == nullptr || m_state == SpectatorState::e_joining) continue;
            const size_t count = c->bytes.size() / row;
            for (size_t i = 0; i < count; ++i) {
                const int64_t f = int64_t{c->firstFrame} + static_cast<int64_t>(i);
                if (f < m_received) continue;
                // A frame after a gap waits for the resend; a full buffer waits for Next.
                if (f > m_received || m_frames.size() >= m_config.maxBufferedFrames) break;
                m_frames.emplace_back(c->bytes.begin() + static_cast<std::ptrdiff_t>(i * row),
                                      c->bytes.begin() + static_cast<std::ptrdiff_t>((i + 1) * row));
                ++m_received;
            }
        }
    }
    const uint64_t silence = now - m_lastHeard;
    if (m_config.interruptTimeoutMicros > 0 && silence > m_config.interruptTimeoutMicros && !m_interrupted &&
        !m_lostReported) {
        m_interrupted = true;
        m_events.push_back({SpectatorEvent::Kind::e_interrupted, m_received});
    }
    if (silence > m_config.timeoutMicros) HostLost();
}

void RollbackSpectator::HostLost() {
    m_alive = false;
    if (m_lostReported) return;
    m_lostReported = true;
    m_interrupted = false;
    m_events.push_back({SpectatorEvent::Kind::e_hostLost, m_received});
}

std::vector<SpectatorEvent> RollbackSpectator::TakeEvents() {
    std::vector<SpectatorEvent> out;
    out.swap(m_events);
    return out;
}

void RollbackSpectator::Flush() {
    const size_t limit = m_transport.MaxDatagram();  // a relay takes its header from it
    const RbHello hello = HelloFor(m_config.determinismVersion, m_shape);
    m_writer.Begin(RollbackHeader{kRollbackProtocolVersion, m_config.matchId});
    m_writer.Add(hello, m_shape, limit);
    if (m_state == SpectatorState::e_incompatible) {
        // The host learns it from our hello and stops sending; a few copies cross a lossy link.
        if (m_incompatibleNotices < kIncompatibleNotices && m_transport.Send(m_config.host, m_writer.Bytes()))
            ++m_incompatibleNotices;
        return;
    }
    if (m_state == SpectatorState::e_joining)
        m_writer.Add(RbJoinRequest{m_attempt}, m_shape, limit);
    else
        m_writer.Add(RbConfirmedAck{m_received}, m_shape, limit);
    // Every chunk that arrived since the last Flush is acked, in as many datagrams as needed.
    size_t at = 0;
    while (at < m_pendingAcks.size()) {
        if (m_writer.Add(m_pendingAcks[at], m_shape, limit)) {
            ++at;
            continue;
        }
        m_transport.Send(m_config.host, m_writer.Bytes());
        m_writer.Begin(RollbackHeader{kRollbackProtocolVersion, m_config.matchId});
        m_writer.Add(hello, m_shape, limit);
        if (!m_writer.Add(m_pendingAcks[at], m_shape, limit)) break;  // cannot happen: an ack is a few bytes
        ++at;
    }
    m_pendingAcks.clear();
    if (m_writer.MessageCount() > 0) m_transport.Send(m_config.host, m_writer.Bytes());
}

bool RollbackSpectator::TakeSnapshot(int32_t& frame, std::vector<uint8_t>& bytes) {
    if (m_state != SpectatorState::e_snapshotReady) return false;
    frame = m_snapshotFrame;
    bytes = std::move(m_snapshot);
    m_snapshot.clear();
    m_state = SpectatorState::e_following;
    return true;
}

bool RollbackSpectator::Next(int32_t& frame, std::vector<uint8_t>& inputs) {
    if (m_state != SpectatorState::e_following || m_frames.empty()) return false;
    frame = m_consumed++;
    inputs = std::move(m_frames.front());
    m_frames.pop_front();
    return true;
}

}  // namespace lockbox::net
