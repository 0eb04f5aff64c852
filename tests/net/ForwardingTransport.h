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
    explicit ForwardingTransport(Transport& inner) : m_inner(inner) {}
    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override {
        return m_inner.Send(peer, bytes, delivery);
    }
    size_t Poll(std::vector<Datagram>& out) override { return m_inner.Poll(out); }
    uint64_t NowMicros() const override { return m_inner.NowMicros(); }
    size_t MaxDatagram() const noexcept override { return m_inner.MaxDatagram(); }
    const TransportStats& Stats() const noexcept override { return m_inner.Stats(); }
    void Disconnect(PeerId peer) override { m_inner.Disconnect(peer); }

private:
    Transport& m_inner;
};

}  // namespace lockbox::net
