// libFuzzer target for the packet decoders: lockstep (net/include/lockbox/net/Protocol.h),
// rollback (RollbackProtocol.h) and the relay header (RelayWire.h). Each input is one datagram:
//   1. decoded with a fixed session shape by each codec; whatever decodes must encode back to
//      the same bytes (the codecs are canonical), and every refusal must leave no messages behind;
//   2. fed to a LockstepServer on a fresh SimNet from a peer that joined properly, so the
//      session handlers see it too. When the first byte is odd the header's token is replaced
//      by the peer's real one, so the fuzzer gets past the token check.
// The server must keep running: one more Update after the datagram, and no crash.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "lockbox/net/LockstepServer.h"
#include "lockbox/net/Protocol.h"
#include "lockbox/net/RelayWire.h"
#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/SimNet.h"
#include "lockbox/state/WorldHash.h"

namespace {

using namespace lockbox::net;

const SessionShape kShape{2, 8};

void CheckCanonical(const uint8_t* data, size_t size) {
    Header header;
    std::vector<Message> messages;
    const DecodeError e = DecodeDatagram({data, size}, kShape, header, messages);
    if (e != DecodeError::e_ok) {
        if (!messages.empty()) std::abort();
        return;
    }
    DatagramWriter w;
    w.Begin(header);
    for (const Message& m : messages)
        if (!w.Add(m, kShape, 1u << 20)) std::abort();  // decoded, so in range
    if (w.Size() != size || std::memcmp(w.Bytes().data(), data, size) != 0) std::abort();
}

const RollbackShape kRollbackShape{2, 8};

void CheckRollbackCanonical(const uint8_t* data, size_t size) {
    RollbackHeader header;
    std::vector<RollbackMessage> messages;
    const DecodeError e = DecodeRollbackDatagram({data, size}, kRollbackShape, header, messages);
    if (e != DecodeError::e_ok) {
        // Only an incompatible hello is handed back with a refusal.
        if (!messages.empty() && e != DecodeError::e_incompatible) std::abort();
        return;
    }
    RollbackDatagramWriter w;
    w.Begin(header);
    for (const RollbackMessage& m : messages)
        if (!w.Add(m, kRollbackShape, 1u << 20)) std::abort();
    if (w.Size() != size || std::memcmp(w.Bytes().data(), data, size) != 0) std::abort();
}

void CheckRelayCanonical(const uint8_t* data, size_t size) {
    const std::optional<RelayFrame> f = ParseRelayFrame({data, size});
    if (!f) return;
    std::vector<uint8_t> again;
    WriteRelayFrame(again, f->kind, f->matchId, f->slot, f->token, f->payload);
    if (again.size() != size || std::memcmp(again.data(), data, size) != 0) std::abort();
}

void FeedServer(const uint8_t* data, size_t size) {
    SimNet net(1);
    SimEndpoint& serverEnd = net.AddEndpoint();
    SimEndpoint& peer = net.AddEndpoint();
    ServerConfig config;
    config.playerCount = kShape.playerCount;
    config.startPlayers = 1;
    config.inputBytes = kShape.inputBytes;
    LockstepServer server(serverEnd, config);

    // Join as slot 0 and learn the token from the Welcome.
    DatagramWriter w;
    w.Begin(Header{});
    w.Add(Hello{lockbox::b2_determinismVersion, 0, kAnySlot, 0}, kShape);
    peer.Send(serverEnd.Index(), w.Bytes());
    net.Advance(1000);
    server.Update();
    net.Advance(1000);
    std::vector<Datagram> got;
    peer.Poll(got);
    uint32_t token = 0;
    for (const Datagram& d : got) {
        Header h;
        std::vector<Message> msgs;
        if (DecodeDatagram(d.bytes, kShape, h, msgs) == DecodeError::e_ok)
            for (const Message& m : msgs)
                if (const auto* welcome = std::get_if<Welcome>(&m)) token = welcome->token;
    }

    std::vector<uint8_t> bytes(data, data + size);
    if (size > kHeaderBytes && (data[0] & 1) != 0) {
        bytes[0] = static_cast<uint8_t>(kProtocolMagic);
        bytes[1] = static_cast<uint8_t>(kProtocolMagic >> 8);
        bytes[2] = kProtocolVersion;
        for (int i = 0; i < 4; ++i) bytes[3 + static_cast<size_t>(i)] = static_cast<uint8_t>(token >> (8 * i));
    }
    if (!bytes.empty() && bytes.size() <= Transport::kMaxDatagram) peer.Send(serverEnd.Index(), bytes);
    for (int i = 0; i < 3; ++i) {
        net.Advance(1000);
        server.Update();
    }
    (void)server.TakeEvents();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    CheckCanonical(data, size);
    CheckRollbackCanonical(data, size);
    CheckRelayCanonical(data, size);
    FeedServer(data, size);
    return 0;
}
