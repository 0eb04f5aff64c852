// RollbackSpectator: the confirmed input stream of a rollback match, and the late join from
// a chunked snapshot (RollbackSpectator.h).

#include "lockbox/net/RollbackSpectator.h"

#include <xxhash.h>

#include <algorithm>

#include "lockbox/net/RollbackSession.h"
#include "session/SnapshotTransfer.h"

namespace lockbox::net {

RollbackSpectator::RollbackSpectator(Transport& transport, RollbackSpectatorConfig config)
    : transport_(transport), config_(config), receiver_(std::make_unique<SnapshotReceiver>(config.maxSnapshotBytes)) {
    config_.players = std::clamp<uint32_t>(config_.players, 1, kRollbackMaxPlayers);
    config_.inputBytes = std::clamp<uint32_t>(config_.inputBytes, 1, kRollbackMaxInputBytes);
    config_.maxSnapshotBytes = std::clamp<uint32_t>(config_.maxSnapshotBytes, 1, kRbMaxSnapshotBytes);
    shape_ = RollbackShape{config_.players, config_.inputBytes};
    lastHeard_ = transport_.NowMicros();
    if (config_.lateJoin) state_ = SpectatorState::e_joining;
}

RollbackSpectator::~RollbackSpectator() = default;

void RollbackSpectator::TakeChunk(const RbSnapshotChunk& c) {
    static_assert(kSnapshotChunkBytes == kRbSnapshotChunkBytes, "SnapshotReceiver chunks must match the wire");
    if (state_ != SpectatorState::e_joining) {
        // A resend of the accepted snapshot means an ack was lost: ack again, or the host
        // would keep resending and never start the input stream.
        if (config_.lateJoin && c.frame == snapshotFrame_ && c.checksum == snapshotChecksum_)
            pendingAcks_.push_back(RbSnapshotAck{c.frame, c.index});
        return;
    }
    if (c.totalSize > config_.maxSnapshotBytes) return;
    if (hasBad_ && c.frame == badFrame_ && c.checksum == badChecksum_) return;
    SnapshotReceiver& r = *receiver_;
    if (r.Active() && c.frame < r.Frame()) return;  // an older snapshot's straggler
    // Same frame, other bytes: the host restarted its snapshot; assemble the new one.
    if (r.Active() && c.frame == r.Frame() && c.checksum != asmChecksum_) r.Reset();
    if (!r.Active() || c.frame != r.Frame()) asmChecksum_ = c.checksum;
    const uint32_t before = r.Received();
    if (!r.Accept(SnapshotChunk{c.frame, c.totalSize, c.index, c.bytes})) return;
    pendingAcks_.push_back(RbSnapshotAck{c.frame, c.index});
    snapshotChunks_ += r.Received() - before;
    if (!r.Complete()) return;
    const std::span<const uint8_t> blob = r.Blob();
    if (r.Failed() || XXH3_64bits(blob.data(), blob.size()) != asmChecksum_) {
        // Corrupt (or not a zstd frame of at most maxSnapshotBytes): never handed out; ask for a fresh snapshot with a
        // new attempt number.
        ++snapshotsRefused_;
        hasBad_ = true;
        badFrame_ = r.Frame();
        badChecksum_ = asmChecksum_;
        ++attempt_;
        r.Reset();
        return;
    }
    snapshotFrame_ = r.Frame();
    snapshotChecksum_ = asmChecksum_;
    snapshot_.assign(blob.begin(), blob.end());
    r.Reset();
    snapshotBytes_ = snapshot_.size();
    received_ = consumed_ = snapshotFrame_;
    frames_.clear();
    state_ = SpectatorState::e_snapshotReady;
}

void RollbackSpectator::Poll() {
    inbox_.clear();
    transport_.Poll(inbox_);
    const uint64_t now = transport_.NowMicros();
    const size_t row = static_cast<size_t>(config_.players) * config_.inputBytes;
    for (const Datagram& d : inbox_) {
        RollbackHeader header;
        if (d.peer != config_.host || state_ == SpectatorState::e_incompatible) {
            ++refused_;
            continue;
        }
        const DecodeError error = DecodeRollbackDatagram(d.bytes, shape_, header, messages_);
        const RollbackIncompatibility why =
            FindIncompatibility(error, header, messages_, config_.matchId, config_.determinismVersion);
        if (why != RollbackIncompatibility::e_none) {
            // Frames from a host that simulates differently would only mislead the game.
            incompatibility_ = why;
            state_ = SpectatorState::e_incompatible;
            frames_.clear();
            snapshot_.clear();
        }
        if (error != DecodeError::e_ok || why != RollbackIncompatibility::e_none) {  // another match id is a reason
            ++refused_;
            continue;
        }
        lastHeard_ = now;
        if (!hostLeft_) {  // a host that said goodbye stays gone; its last datagrams still count
            alive_ = true;
            if (interrupted_ || lostReported_) events_.push_back({SpectatorEvent::Kind::e_resumed, received_});
            interrupted_ = lostReported_ = false;
        }
        for (const RollbackMessage& m : messages_) {
            if (std::holds_alternative<RbDisconnect>(m)) {
                hostLeft_ = true;
                HostLost();
            }
            if (const auto* chunk = std::get_if<RbSnapshotChunk>(&m)) TakeChunk(*chunk);
            const auto* c = std::get_if<RbConfirmed>(&m);
            // Before its snapshot a late joiner has no frame to continue from.
            if (c == nullptr || state_ == SpectatorState::e_joining) continue;
            const size_t count = c->bytes.size() / row;
            for (size_t i = 0; i < count; ++i) {
                const int64_t f = int64_t{c->firstFrame} + static_cast<int64_t>(i);
                if (f < received_) continue;
                // A frame after a gap waits for the resend; a full buffer waits for Next.
                if (f > received_ || frames_.size() >= config_.maxBufferedFrames) break;
                frames_.emplace_back(c->bytes.begin() + static_cast<std::ptrdiff_t>(i * row),
                                     c->bytes.begin() + static_cast<std::ptrdiff_t>((i + 1) * row));
                ++received_;
            }
        }
    }
    const uint64_t silence = now - lastHeard_;
    if (config_.interruptTimeoutMicros > 0 && silence > config_.interruptTimeoutMicros && !interrupted_ &&
        !lostReported_) {
        interrupted_ = true;
        events_.push_back({SpectatorEvent::Kind::e_interrupted, received_});
    }
    if (silence > config_.timeoutMicros) HostLost();
}

void RollbackSpectator::HostLost() {
    alive_ = false;
    if (lostReported_) return;
    lostReported_ = true;
    interrupted_ = false;
    events_.push_back({SpectatorEvent::Kind::e_hostLost, received_});
}

std::vector<SpectatorEvent> RollbackSpectator::TakeEvents() {
    std::vector<SpectatorEvent> out;
    out.swap(events_);
    return out;
}

void RollbackSpectator::Flush() {
    const size_t limit = transport_.MaxDatagram();  // a relay takes its header from it
    const RbHello hello = HelloFor(config_.determinismVersion, shape_);
    writer_.Begin(RollbackHeader{kRollbackProtocolVersion, config_.matchId});
    writer_.Add(hello, shape_, limit);
    if (state_ == SpectatorState::e_incompatible) {
        // The host learns it from our hello and stops sending; a few copies cross a lossy link.
        if (incompatibleNotices_ < kIncompatibleNotices && transport_.Send(config_.host, writer_.Bytes()))
            ++incompatibleNotices_;
        return;
    }
    if (state_ == SpectatorState::e_joining)
        writer_.Add(RbJoinRequest{attempt_}, shape_, limit);
    else
        writer_.Add(RbConfirmedAck{received_}, shape_, limit);
    // Every chunk that arrived since the last Flush is acked, in as many datagrams as needed.
    size_t at = 0;
    while (at < pendingAcks_.size()) {
        if (writer_.Add(pendingAcks_[at], shape_, limit)) {
            ++at;
            continue;
        }
        transport_.Send(config_.host, writer_.Bytes());
        writer_.Begin(RollbackHeader{kRollbackProtocolVersion, config_.matchId});
        writer_.Add(hello, shape_, limit);
        if (!writer_.Add(pendingAcks_[at], shape_, limit)) break;  // cannot happen: an ack is a few bytes
        ++at;
    }
    pendingAcks_.clear();
    if (writer_.MessageCount() > 0) transport_.Send(config_.host, writer_.Bytes());
}

bool RollbackSpectator::TakeSnapshot(int32_t& frame, std::vector<uint8_t>& bytes) {
    if (state_ != SpectatorState::e_snapshotReady) return false;
    frame = snapshotFrame_;
    bytes = std::move(snapshot_);
    snapshot_.clear();
    state_ = SpectatorState::e_following;
    return true;
}

bool RollbackSpectator::Next(int32_t& frame, std::vector<uint8_t>& inputs) {
    if (state_ != SpectatorState::e_following || frames_.empty()) return false;
    frame = consumed_++;
    inputs = std::move(frames_.front());
    frames_.pop_front();
    return true;
}

}  // namespace lockbox::net
