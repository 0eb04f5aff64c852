// RollbackSpectator: the confirmed input stream of a rollback match, and the late join from
// a chunked snapshot (RollbackSpectator.h).

#include "lockbox/net/RollbackSpectator.h"

#include <xxhash.h>

#include <algorithm>
#include <cstring>

#include "lockbox/net/RollbackSession.h"

namespace lockbox::net {

RollbackSpectator::RollbackSpectator(Transport& transport, RollbackSpectatorConfig config)
    : transport_(transport), config_(config) {
    config_.players = std::clamp<uint32_t>(config_.players, 1, kRollbackMaxPlayers);
    config_.inputBytes = std::clamp<uint32_t>(config_.inputBytes, 1, kRollbackMaxInputBytes);
    config_.maxSnapshotBytes = std::clamp<uint32_t>(config_.maxSnapshotBytes, 1, kRbMaxSnapshotBytes);
    shape_ = RollbackShape{config_.players, config_.inputBytes};
    lastHeard_ = transport_.NowMicros();
    if (config_.lateJoin) state_ = SpectatorState::e_joining;
}

void RollbackSpectator::TakeChunk(const RbSnapshotChunk& c) {
    if (state_ != SpectatorState::e_joining) {
        // A resend of the accepted snapshot means an ack was lost: ack again, or the host
        // would keep resending and never start the input stream.
        if (config_.lateJoin && c.frame == snapshotFrame_ && c.checksum == snapshotChecksum_)
            pendingAcks_.push_back(RbSnapshotAck{c.frame, c.index});
        return;
    }
    if (c.totalSize > config_.maxSnapshotBytes) return;
    if (hasBad_ && c.frame == badFrame_ && c.checksum == badChecksum_) return;
    if (assembling_ && c.frame < asmFrame_) return;  // an older snapshot's straggler
    if (!assembling_ || c.frame != asmFrame_ || c.totalSize != asmTotal_ || c.checksum != asmChecksum_) {
        // A newer (or different) snapshot: the host restarted; assemble that one instead.
        assembling_ = true;
        asmFrame_ = c.frame;
        asmTotal_ = c.totalSize;
        asmChecksum_ = c.checksum;
        asmCount_ = 0;
        asm_.assign(asmTotal_, 0);
        asmHave_.assign((size_t{asmTotal_} + kRbSnapshotChunkBytes - 1) / kRbSnapshotChunkBytes, 0);
    }
    const size_t offset = size_t{c.index} * kRbSnapshotChunkBytes;
    // The codec checked index and length against totalSize; check again before copying.
    if (c.index >= asmHave_.size() || offset + c.bytes.size() > asm_.size()) return;
    pendingAcks_.push_back(RbSnapshotAck{c.frame, c.index});
    if (asmHave_[c.index] != 0) return;
    if (!c.bytes.empty()) std::memcpy(asm_.data() + offset, c.bytes.data(), c.bytes.size());
    asmHave_[c.index] = 1;
    ++asmCount_;
    ++snapshotChunks_;
    if (asmCount_ < asmHave_.size()) return;
    assembling_ = false;
    if (XXH3_64bits(asm_.data(), asm_.size()) != asmChecksum_) {
        // Corrupt: never handed out; ask for a fresh snapshot with a new attempt number.
        ++snapshotsRefused_;
        hasBad_ = true;
        badFrame_ = asmFrame_;
        badChecksum_ = asmChecksum_;
        ++attempt_;
        asm_.clear();
        asmHave_.clear();
        return;
    }
    snapshotFrame_ = asmFrame_;
    snapshotChecksum_ = asmChecksum_;
    snapshot_ = std::move(asm_);
    asm_.clear();
    asmHave_.clear();
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
        if (d.peer != config_.host || DecodeRollbackDatagram(d.bytes, shape_, header, messages_) != DecodeError::e_ok ||
            header.matchId != config_.matchId) {
            ++refused_;
            continue;
        }
        lastHeard_ = now;
        alive_ = true;
        for (const RollbackMessage& m : messages_) {
            if (std::holds_alternative<RbDisconnect>(m)) alive_ = false;
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
    if (now - lastHeard_ > config_.timeoutMicros) alive_ = false;
}

void RollbackSpectator::Flush() {
    writer_.Begin(RollbackHeader{kRollbackProtocolVersion, config_.matchId});
    if (state_ == SpectatorState::e_joining) writer_.Add(RbJoinRequest{attempt_}, shape_);
    else writer_.Add(RbConfirmedAck{received_}, shape_);
    // Every chunk that arrived since the last Flush is acked, in as many datagrams as needed.
    size_t at = 0;
    while (at < pendingAcks_.size()) {
        if (writer_.Add(pendingAcks_[at], shape_)) {
            ++at;
            continue;
        }
        transport_.Send(config_.host, writer_.Bytes());
        writer_.Begin(RollbackHeader{kRollbackProtocolVersion, config_.matchId});
        if (!writer_.Add(pendingAcks_[at], shape_)) break;  // cannot happen: an ack is a few bytes
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
