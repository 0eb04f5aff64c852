// The relay (RelayWire.h, RelayServer.h, RelayedTransport.h): header codec, slot binding by
// token, forwarding and every refusal, on a SimNet.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/RelayServer.h"
#include "lockbox/net/RelayWire.h"
#include "lockbox/net/RelayedTransport.h"
#include "lockbox/net/SimNet.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

constexpr uint32_t kMatch = 42;

std::vector<uint8_t> Bytes(std::initializer_list<uint8_t> b) { return b; }

TEST(RelayWire, RoundTripsEveryKind) {
    std::vector<uint8_t> out;
    WriteRelayFrame(out, RelayKind::e_join, kMatch, 3, 0x1122334455667788ull);
    ASSERT_EQ(out.size(), kRelayHeaderBytes + 8);
    auto f = ParseRelayFrame(out);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->kind, RelayKind::e_join);
    EXPECT_EQ(f->matchId, kMatch);
    EXPECT_EQ(f->slot, 3);
    EXPECT_EQ(f->token, 0x1122334455667788ull);

    WriteRelayFrame(out, RelayKind::e_welcome, kMatch, 7);
    f = ParseRelayFrame(out);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->kind, RelayKind::e_welcome);
    EXPECT_EQ(f->slot, 7);

    const auto payload = Bytes({9, 8, 7});
    WriteRelayFrame(out, RelayKind::e_toSlot, kMatch, 1, 0, payload);
    f = ParseRelayFrame(out);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->kind, RelayKind::e_toSlot);
    EXPECT_EQ(std::vector<uint8_t>(f->payload.begin(), f->payload.end()), payload);
}

TEST(RelayWire, RefusesMalformedHeaders) {
    std::vector<uint8_t> good;
    WriteRelayFrame(good, RelayKind::e_toSlot, kMatch, 1, 0, Bytes({1}));
    ASSERT_TRUE(ParseRelayFrame(good));
    for (size_t cut = 0; cut < good.size(); ++cut)
        EXPECT_FALSE(ParseRelayFrame(std::span<const uint8_t>(good.data(), cut))) << "cut at " << cut;
    auto bad = good;
    bad[0] = 'X';
    EXPECT_FALSE(ParseRelayFrame(bad));
    bad = good;
    bad[2] = kRelayVersion + 1;
    EXPECT_FALSE(ParseRelayFrame(bad));
    bad = good;
    bad[3] = 0;
    EXPECT_FALSE(ParseRelayFrame(bad));
    bad[3] = 5;
    EXPECT_FALSE(ParseRelayFrame(bad));
    bad = good;
    bad[8] = kRelayMaxSlots;
    EXPECT_FALSE(ParseRelayFrame(bad));
    // A join must be exactly header + token; a welcome exactly the header.
    std::vector<uint8_t> join;
    WriteRelayFrame(join, RelayKind::e_join, kMatch, 0, 5);
    join.push_back(0);
    EXPECT_FALSE(ParseRelayFrame(join));
    std::vector<uint8_t> welcome;
    WriteRelayFrame(welcome, RelayKind::e_welcome, kMatch, 0);
    welcome.push_back(0);
    EXPECT_FALSE(ParseRelayFrame(welcome));
}

// A relay and `members` relayed members on one SimNet (perfect links unless set).
struct RelayRig {
    SimNet net{7};
    SimEndpoint& relayEnd = net.AddEndpoint();
    std::vector<SimEndpoint*> ends;
    std::unique_ptr<RelayServer> relay;
    std::vector<std::unique_ptr<RelayedTransport>> members;

    explicit RelayRig(uint32_t count) {
        RelayServerConfig rc;
        rc.matchId = kMatch;
        for (uint32_t i = 0; i < count; ++i) rc.tokens.push_back(1000 + i);
        relay = std::make_unique<RelayServer>(relayEnd, rc);
        for (uint32_t i = 0; i < count; ++i) ends.push_back(&net.AddEndpoint());
        for (uint32_t i = 0; i < count; ++i) members.push_back(Join(*ends[i], i, 1000 + i, count));
    }
    std::unique_ptr<RelayedTransport> Join(SimEndpoint& end, uint32_t slot, uint64_t token, uint32_t slots) {
        RelayedTransportConfig c;
        c.relay = relayEnd.Index();
        c.matchId = kMatch;
        c.slot = slot;
        c.slots = slots;
        c.token = token;
        return std::make_unique<RelayedTransport>(end, c);
    }
    // Advances the clock in 1 ms steps, polling the relay and draining every member.
    std::vector<std::vector<Datagram>> Run(uint64_t micros) {
        std::vector<std::vector<Datagram>> got(members.size());
        for (uint64_t t = 0; t < micros; t += 1000) {
            net.Advance(1000);
            relay->Poll();
            for (size_t i = 0; i < members.size(); ++i) members[i]->Poll(got[i]);
        }
        return got;
    }
};

TEST(RelayServer, JoinsAndForwardsWithTheSourceSlot) {
    RelayRig rig(3);
    rig.Run(5000);
    for (auto& m : rig.members) EXPECT_TRUE(m->Joined());
    EXPECT_EQ(rig.relay->SlotPeer(1), rig.ends[1]->Index());
    EXPECT_EQ(rig.members[0]->MaxDatagram(), Transport::kMaxDatagram - kRelayHeaderBytes);

    const auto hello = Bytes({1, 2, 3, 4});
    ASSERT_TRUE(rig.members[0]->Send(2, hello));
    ASSERT_TRUE(rig.members[2]->Send(1, Bytes({5})));
    const auto got = rig.Run(5000);
    ASSERT_EQ(got[2].size(), 1u);
    EXPECT_EQ(got[2][0].peer, 0u);  // the source slot, not a transport PeerId
    EXPECT_EQ(got[2][0].bytes, hello);
    ASSERT_EQ(got[1].size(), 1u);
    EXPECT_EQ(got[1][0].peer, 2u);
    EXPECT_TRUE(got[0].empty());
    EXPECT_EQ(rig.relay->Stats().forwarded, 2u);
    EXPECT_EQ(rig.relay->Stats().forwardedBytes, 5u);
    EXPECT_EQ(rig.relay->Stats().refused, 0u);
}

TEST(RelayServer, ServesItsLargestSlotCount) {
    // 8 players and 32 spectators need 40 slots; the relay serves up to kRelayMaxSlots.
    RelayRig rig(kRelayMaxSlots);
    rig.Run(5000);
    for (auto& m : rig.members) EXPECT_TRUE(m->Joined());
    const uint32_t last = kRelayMaxSlots - 1;
    ASSERT_TRUE(rig.members[0]->Send(last, Bytes({7})));
    ASSERT_TRUE(rig.members[last]->Send(0, Bytes({9})));
    const auto got = rig.Run(5000);
    ASSERT_EQ(got[last].size(), 1u);
    EXPECT_EQ(got[last][0].peer, 0u);
    ASSERT_EQ(got[0].size(), 1u);
    EXPECT_EQ(got[0][0].peer, last);
    EXPECT_EQ(rig.relay->Stats().refused, 0u);
    // One slot more is refused by both ends.
    RelayServerConfig tooMany;
    tooMany.tokens.assign(kRelayMaxSlots + 1, 1);
    EXPECT_THROW(RelayServer(rig.relayEnd, tooMany), std::invalid_argument);
    EXPECT_THROW(rig.Join(*rig.ends[0], 0, 1, kRelayMaxSlots + 1), std::invalid_argument);
}

TEST(RelayedTransport, RefusesBadSendsLocally) {
    RelayRig rig(2);
    rig.Run(3000);
    const std::vector<uint8_t> big(rig.members[0]->MaxDatagram() + 1, 1);
    const std::vector<uint8_t> max(rig.members[0]->MaxDatagram(), 1);
    EXPECT_FALSE(rig.members[0]->Send(0, Bytes({1})));  // itself
    EXPECT_FALSE(rig.members[0]->Send(2, Bytes({1})));  // outside the match
    EXPECT_FALSE(rig.members[0]->Send(1, {}));
    EXPECT_FALSE(rig.members[0]->Send(1, big));
    EXPECT_EQ(rig.members[0]->Stats().sendFailures, 4u);
    EXPECT_TRUE(rig.members[0]->Send(1, max));
    const auto got = rig.Run(3000);
    ASSERT_EQ(got[1].size(), 1u);
    EXPECT_EQ(got[1][0].bytes, max);
    EXPECT_THROW(rig.Join(*rig.ends[0], 2, 1, 2), std::invalid_argument);
    EXPECT_THROW(rig.Join(*rig.ends[0], 0, 1, 1), std::invalid_argument);
    RelayServerConfig one;
    one.tokens = {1};
    EXPECT_THROW(RelayServer(rig.relayEnd, one), std::invalid_argument);
}

TEST(RelayServer, RefusesStrangersBadTokensAndBadSlots) {
    RelayRig rig(3);
    SimEndpoint& stranger = rig.net.AddEndpoint();
    rig.Run(3000);
    std::vector<uint8_t> d;
    const auto payload = Bytes({1});
    // No slot: data is refused.
    WriteRelayFrame(d, RelayKind::e_toSlot, kMatch, 0, 0, payload);
    stranger.Send(rig.relayEnd.Index(), d);
    // Wrong token for slot 1: refused, slot 1 stays with its member.
    WriteRelayFrame(d, RelayKind::e_join, kMatch, 1, 999);
    stranger.Send(rig.relayEnd.Index(), d);
    // Another match.
    WriteRelayFrame(d, RelayKind::e_join, kMatch + 1, 1, 1001);
    stranger.Send(rig.relayEnd.Index(), d);
    // A slot beyond the relay's three.
    WriteRelayFrame(d, RelayKind::e_join, kMatch, 5, 1005);
    stranger.Send(rig.relayEnd.Index(), d);
    // Relay-to-member kinds sent to the relay.
    WriteRelayFrame(d, RelayKind::e_fromSlot, kMatch, 0, 0, payload);
    rig.ends[1]->Send(rig.relayEnd.Index(), d);
    // A member addressing itself, and garbage.
    WriteRelayFrame(d, RelayKind::e_toSlot, kMatch, 1, 0, payload);
    rig.ends[1]->Send(rig.relayEnd.Index(), d);
    rig.ends[1]->Send(rig.relayEnd.Index(), Bytes({'L', 'Y', 9}));
    // Member 1 tries to take a second seat (slot 2's token is right, but one address holds one).
    WriteRelayFrame(d, RelayKind::e_join, kMatch, 2, 1002);
    rig.ends[1]->Send(rig.relayEnd.Index(), d);
    const auto got = rig.Run(3000);
    EXPECT_EQ(rig.relay->Stats().refused, 8u);
    EXPECT_EQ(rig.relay->Stats().forwarded, 0u);
    EXPECT_EQ(rig.relay->SlotPeer(1), rig.ends[1]->Index());
    EXPECT_EQ(rig.relay->SlotPeer(2), rig.ends[2]->Index());
    for (const auto& g : got) EXPECT_TRUE(g.empty());
}

TEST(RelayServer, SameTokenFromANewAddressTakesTheSlotBack) {
    RelayRig rig(2);
    rig.Run(3000);
    SimEndpoint& moved = rig.net.AddEndpoint();
    rig.members[1] = rig.Join(moved, 1, 1001, 2);  // member 1 after a NAT rebinding
    rig.Run(3000);
    EXPECT_TRUE(rig.members[1]->Joined());
    EXPECT_EQ(rig.relay->SlotPeer(1), moved.Index());
    EXPECT_EQ(rig.relay->Stats().rebinds, 1u);
    ASSERT_TRUE(rig.members[0]->Send(1, Bytes({4, 2})));
    const auto got = rig.Run(3000);
    ASSERT_EQ(got[1].size(), 1u);
    EXPECT_EQ(got[1][0].peer, 0u);
    // The old address no longer speaks for slot 1.
    std::vector<uint8_t> d;
    WriteRelayFrame(d, RelayKind::e_toSlot, kMatch, 0, 0, Bytes({1}));
    rig.ends[1]->Send(rig.relayEnd.Index(), d);
    const auto after = rig.Run(3000);
    EXPECT_TRUE(after[0].empty());
}

TEST(RelayServer, AReleasedMemberGetsNothingAndMayJoinAnotherSlot) {
    RelayRig rig(3);
    rig.Run(3000);
    EXPECT_EQ(rig.relay->Release(rig.ends[1]->Index()), 1);
    EXPECT_EQ(rig.relay->SlotPeer(1), kNoPeer);
    EXPECT_EQ(rig.relay->Release(rig.ends[1]->Index()), -1);  // holds nothing now
    ASSERT_TRUE(rig.members[0]->Send(1, Bytes({4, 2})));
    auto got = rig.Run(3000);
    EXPECT_TRUE(got[1].empty());
    // Its next join may claim any free slot (one address still holds one slot at a time).
    EXPECT_EQ(rig.relay->Release(rig.ends[2]->Index()), 2);
    rig.members[1] = rig.Join(*rig.ends[1], 2, 1002, 3);
    rig.Run(3000);
    EXPECT_TRUE(rig.members[1]->Joined());
    EXPECT_EQ(rig.relay->SlotPeer(2), rig.ends[1]->Index());
}

TEST(RelayedTransport, KeepsJoiningUntilWelcomedOverALossyLink) {
    RelayRig rig(2);
    LinkProfile lossy;
    lossy.lossPpm = 600000;  // 60 % each way
    rig.net.SetAllLinks(lossy);
    rig.members[0] = rig.Join(*rig.ends[0], 0, 1000, 2);
    rig.members[1] = rig.Join(*rig.ends[1], 1, 1001, 2);
    rig.Run(3000000);
    EXPECT_TRUE(rig.members[0]->Joined());
    EXPECT_TRUE(rig.members[1]->Joined());
    // Members only ever see datagrams from the relay: one from elsewhere is dropped.
    std::vector<uint8_t> d;
    WriteRelayFrame(d, RelayKind::e_fromSlot, kMatch, 1, 0, Bytes({1}));
    rig.net.SetAllLinks(LinkProfile{});
    rig.ends[1]->Send(rig.ends[0]->Index(), d);
    const auto got = rig.Run(3000);
    EXPECT_TRUE(got[0].empty());
    EXPECT_GE(rig.members[0]->Stats().droppedUnknown, 1u);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
