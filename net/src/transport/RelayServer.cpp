// RelayServer: slot binding by token and forwarding (RelayServer.h).
#include "lockbox/net/RelayServer.h"

#include <stdexcept>

namespace lockbox::net {

RelayServer::RelayServer(Transport& transport, RelayServerConfig config)
    : transport_(transport), config_(std::move(config)) {
    if (config_.tokens.size() < 2 || config_.tokens.size() > kRelayMaxSlots)
        throw std::invalid_argument("RelayServer: the slot count (tokens) must be in 2 .. 32");
    slotPeer_.assign(config_.tokens.size(), kNoPeer);
}

PeerId RelayServer::SlotPeer(uint32_t slot) const noexcept {
    return slot < slotPeer_.size() ? slotPeer_[slot] : kNoPeer;
}

int RelayServer::SlotOf(PeerId peer) const noexcept {
    // A handful of slots: a linear scan in slot order.
    for (size_t s = 0; s < slotPeer_.size(); ++s)
        if (slotPeer_[s] == peer) return static_cast<int>(s);
    return -1;
}

void RelayServer::Poll() {
    inbox_.clear();
    transport_.Poll(inbox_);
    for (const Datagram& d : inbox_) Handle(d);
}

void RelayServer::Handle(const Datagram& d) {
    const std::optional<RelayFrame> f = ParseRelayFrame(d.bytes);
    if (!f || f->matchId != config_.matchId || f->slot >= slotPeer_.size()) {
        ++stats_.refused;
        return;
    }
    if (f->kind == RelayKind::e_join) {
        if (f->token != config_.tokens[f->slot]) {
            ++stats_.refused;
            return;
        }
        const int held = SlotOf(d.peer);
        if (held >= 0 && held != f->slot) {
            // One address, one slot: a member cannot hold two seats.
            ++stats_.refused;
            return;
        }
        if (slotPeer_[f->slot] != d.peer) {
            if (slotPeer_[f->slot] != kNoPeer) ++stats_.rebinds;
            slotPeer_[f->slot] = d.peer;
        }
        ++stats_.joins;
        // Answer every join: the member repeats it until a welcome gets through.
        WriteRelayFrame(out_, RelayKind::e_welcome, config_.matchId, f->slot);
        if (!transport_.Send(d.peer, out_, Delivery::e_reliable)) ++stats_.sendFailures;
        return;
    }
    if (f->kind != RelayKind::e_toSlot) {
        ++stats_.refused;  // welcome and from-slot only travel relay -> member
        return;
    }
    const int from = SlotOf(d.peer);
    const PeerId to = slotPeer_[f->slot];
    if (from < 0 || to == kNoPeer || static_cast<int>(f->slot) == from) {
        ++stats_.refused;
        return;
    }
    WriteRelayFrame(out_, RelayKind::e_fromSlot, config_.matchId, static_cast<uint8_t>(from), 0, f->payload);
    if (!transport_.Send(to, out_)) {
        ++stats_.sendFailures;
        return;
    }
    ++stats_.forwarded;
    stats_.forwardedBytes += f->payload.size();
}

}  // namespace lockbox::net
