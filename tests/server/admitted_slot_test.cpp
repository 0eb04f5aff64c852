// LockstepServer's admission hook (ServerConfig::admittedSlot): an admitted client gets the slot
// its admission names whatever it asks for, anyone else is refused.

#include <cstdint>
#include <map>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/LockstepServer.h"
#include "lockbox/net/Protocol.h"
#include "lockbox/net/SimNet.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

// Sends a Hello from `from` asking for `requested`, and returns the server's answer.
Message HelloAnswer(SimNet& simnet, LockstepServer& server, SimEndpoint& from, PeerId serverId, uint8_t requested,
                    uint32_t token = 0) {
    DatagramWriter w;
    w.Begin(Header{kProtocolVersion, token, 0});
    w.Add(Hello{b2_determinismVersion, token, requested, 0}, SessionShape{});
    EXPECT_TRUE(from.Send(serverId, w.Bytes()));
    simnet.Advance(10'000);
    server.Update();
    simnet.Advance(10'000);
    std::vector<Datagram> got;
    from.Poll(got);
    EXPECT_EQ(got.size(), 1u);
    if (got.empty()) return KeepAlive{};
    Header h;
    std::vector<Message> messages;
    EXPECT_EQ(DecodeDatagram(got[0].bytes, SessionShape{}, h, messages), DecodeError::e_ok);
    return messages.empty() ? Message{KeepAlive{}} : messages[0];
}

TEST(AdmittedSlot, TheAdmissionDecidesTheSlot) {
    SimNet simnet(3);
    SimEndpoint& serverEnd = simnet.AddEndpoint();
    SimEndpoint& a = simnet.AddEndpoint();
    SimEndpoint& b = simnet.AddEndpoint();
    SimEndpoint& stranger = simnet.AddEndpoint();
    std::map<PeerId, int32_t> admitted{{a.Index(), 2}, {b.Index(), 2}};
    ServerConfig config;
    config.playerCount = 3;
    config.admittedSlot = [&](PeerId peer) {
        const auto it = admitted.find(peer);
        return it == admitted.end() ? -1 : it->second;
    };
    LockstepServer server(serverEnd, config);

    // Asks for slot 0, gets the admitted slot 2.
    const Message first = HelloAnswer(simnet, server, a, serverEnd.Index(), 0);
    ASSERT_TRUE(std::holds_alternative<Welcome>(first));
    EXPECT_EQ(std::get<Welcome>(first).slot, 2);
    // Another peer admitted to the same slot while it is live: slot taken.
    const Message second = HelloAnswer(simnet, server, b, serverEnd.Index(), kAnySlot);
    ASSERT_TRUE(std::holds_alternative<Reject>(second));
    EXPECT_EQ(std::get<Reject>(second).reason, RejectReason::e_slotTaken);
    // Not admitted at all: bad token.
    const Message third = HelloAnswer(simnet, server, stranger, serverEnd.Index(), kAnySlot);
    ASSERT_TRUE(std::holds_alternative<Reject>(third));
    EXPECT_EQ(std::get<Reject>(third).reason, RejectReason::e_badToken);
    EXPECT_EQ(server.Slot(2).peer, a.Index());
    EXPECT_EQ(server.Slot(0).state, SlotInfo::State::e_free);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
