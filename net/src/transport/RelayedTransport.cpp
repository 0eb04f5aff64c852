// RelayedTransport: slot-addressed datagrams through a RelayServer (RelayedTransport.h).
#include "lockbox/net/RelayedTransport.h"

#include <stdexcept>

namespace lockbox::net {

RelayedTransport::RelayedTransport(Transport& inner, RelayedTransportConfig config) : inner_(inner), config_(config) {
    if (config_.slots < 2 || config_.slots > kRelayMaxSlots)
        throw std::invalid_argument("RelayedTransport: slots must be in 2 .. 32");
    if (config_.slot >= config_.slots) throw std::invalid_argument("RelayedTransport: slot must be < slots");
    if (config_.relay == kNoPeer) throw std::invalid_argument("RelayedTransport: no relay peer");
    if (config_.joinRetryMicros == 0) throw std::invalid_argument("RelayedTransport: joinRetryMicros must be >= 1");
    MaybeJoin();
}

void RelayedTransport::MaybeJoin() {
    if (joined_) return;
    const uint64_t now = inner_.NowMicros();
    if (joinSent_ && now - lastJoin_ < config_.joinRetryMicros) return;
    WriteRelayFrame(out_, RelayKind::e_join, config_.matchId, static_cast<uint8_t>(config_.slot), config_.token);
    inner_.Send(config_.relay, out_, Delivery::e_reliable);
    joinSent_ = true;
    lastJoin_ = now;
}

bool RelayedTransport::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    MaybeJoin();
    if (peer >= config_.slots || peer == config_.slot || bytes.empty() || bytes.size() > MaxDatagram()) {
        ++stats_.sendFailures;
        return false;
    }
    WriteRelayFrame(out_, RelayKind::e_toSlot, config_.matchId, static_cast<uint8_t>(peer), 0, bytes);
    if (!inner_.Send(config_.relay, out_, delivery)) {
        ++stats_.sendFailures;
        return false;
    }
    ++stats_.datagramsSent;
    stats_.payloadBytesSent += bytes.size();
    stats_.wireBytesSent += out_.size();
    return true;
}

size_t RelayedTransport::Poll(std::vector<Datagram>& out) {
    inbox_.clear();
    inner_.Poll(inbox_);
    size_t added = 0;
    for (Datagram& d : inbox_) {
        const std::optional<RelayFrame> f =
            d.peer == config_.relay ? ParseRelayFrame(d.bytes) : std::optional<RelayFrame>{};
        if (!f || f->matchId != config_.matchId) {
            ++stats_.droppedUnknown;
            continue;
        }
        if (f->kind == RelayKind::e_welcome && f->slot == config_.slot) {
            joined_ = true;
            continue;
        }
        if (f->kind != RelayKind::e_fromSlot || f->slot >= config_.slots || f->slot == config_.slot) {
            ++stats_.droppedUnknown;
            continue;
        }
        Datagram& o = out.emplace_back();
        o.peer = f->slot;
        o.bytes.assign(f->payload.begin(), f->payload.end());
        ++stats_.datagramsReceived;
        stats_.payloadBytesReceived += o.bytes.size();
        ++added;
    }
    MaybeJoin();
    return added;
}

}  // namespace lockbox::net
