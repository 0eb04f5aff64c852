#pragma once
// A Transport that hands every call to another one; tests derive from it and override Send to
// drop, count or inspect what goes out.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/net/Transport.h"

namespace lockbox::net {

class ForwardingTransport : public Transport {
public:
    explicit ForwardingTransport(Transport& inner) : inner_(inner) {}
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override {
        return inner_.Send(peer, bytes, delivery);
    }
    size_t Poll(std::vector<Datagram>& out) override { return inner_.Poll(out); }
    uint64_t NowMicros() const override { return inner_.NowMicros(); }
    size_t MaxDatagram() const noexcept override { return inner_.MaxDatagram(); }
    const TransportStats& Stats() const noexcept override { return inner_.Stats(); }
    void Disconnect(PeerId peer) override { inner_.Disconnect(peer); }

private:
    Transport& inner_;
};

}  // namespace lockbox::net
