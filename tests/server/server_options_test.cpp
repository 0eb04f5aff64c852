// lockbox_server's options for spectator matches: the relay's slot bound and the budget of the
// player that hosts the spectators.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ServerOptions.h"
#include "lockbox/net/RelayWire.h"

namespace lockbox::server {
namespace LOCKBOX_TEST_FILE {

int Read(std::vector<std::string> args, ServerOptions& out) {
    args.insert(args.begin(), {"lockbox_server", "--token-key-file", "key"});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    return ReadOptions(static_cast<int>(argv.size()), argv.data(), out);
}

TEST(ServerOptions, EightPlayersAndThirtyTwoSpectatorsFitOneRelay) {
    ServerOptions o;
    ASSERT_EQ(Read({"--match-kind", "rollback-relay", "--players-per-match", "8", "--spectators-per-match", "32"}, o),
              0);
    EXPECT_EQ(o.spectatorsPerMatch, 32u);
    EXPECT_FALSE(o.spectatorHostBytesPerSecond);  // the role's default: the host decides
    // Players and spectators together up to the relay's slot count, not one more.
    const std::string most = std::to_string(net::kRelayMaxSlots - 8);
    EXPECT_EQ(Read({"--match-kind", "rollback-relay", "--players-per-match", "8", "--spectators-per-match", most}, o),
              0);
    const std::string tooMany = std::to_string(net::kRelayMaxSlots - 7);
    EXPECT_EQ(
        Read({"--match-kind", "rollback-relay", "--players-per-match", "8", "--spectators-per-match", tooMany}, o), 2);
}

TEST(ServerOptions, TheSpectatorsHostBudgetIsAnOptionOfItsOwn) {
    ServerOptions o;
    ASSERT_EQ(
        Read({"--match-kind", "rollback-relay", "--spectators-per-match", "4", "--spectator-host-bandwidth", "500000"},
             o),
        0);
    ASSERT_TRUE(o.spectatorHostBytesPerSecond);
    EXPECT_EQ(*o.spectatorHostBytesPerSecond, 500000u);
    EXPECT_EQ(Read({"--spectator-host-bandwidth", "lots"}, o), 2);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::server
