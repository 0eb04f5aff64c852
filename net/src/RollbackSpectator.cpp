// RollbackSpectator: the confirmed input stream of a rollback match (RollbackSpectator.h).

#include "lockbox/net/RollbackSpectator.h"

#include <algorithm>

#include "lockbox/net/RollbackSession.h"

namespace lockbox::net {

RollbackSpectator::RollbackSpectator(Transport& transport, RollbackSpectatorConfig config)
    : transport_(transport), config_(config) {
    config_.players = std::clamp<uint32_t>(config_.players, 1, kRollbackMaxPlayers);
    config_.inputBytes = std::clamp<uint32_t>(config_.inputBytes, 1, kRollbackMaxInputBytes);
    shape_ = RollbackShape{config_.players, config_.inputBytes};
    lastHeard_ = transport_.NowMicros();
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
            const auto* c = std::get_if<RbConfirmed>(&m);
            if (c == nullptr) continue;
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
    writer_.Add(RbConfirmedAck{received_}, shape_);
    transport_.Send(config_.host, writer_.Bytes());
}

bool RollbackSpectator::Next(int32_t& frame, std::vector<uint8_t>& inputs) {
    if (frames_.empty()) return false;
    frame = consumed_++;
    inputs = std::move(frames_.front());
    frames_.pop_front();
    return true;
}

}  // namespace lockbox::net
