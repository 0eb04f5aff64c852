// The start phase on real sockets at the spacing: two peers on 127.0.0.1 started 3 s
// apart, in either order, play the same match (about 7 s of wall time for both orders).

#include <chrono>

#include <gtest/gtest.h>

#include "../rollback_udp_start.h"

namespace lockbox::net::rbtest {
namespace {

TEST(RollbackUdpStart, PeersStartedThreeSecondsApartAgree) {
    for (uint32_t late = 0; late < 2; ++late) {
        SCOPED_TRACE(::testing::Message() << "late side " << late);
        UdpStartResult r;
        RunUdpStaggered(r, late, std::chrono::seconds(3), 120);
        ExpectUdpStartedTogether(r, 120);
    }
}

}  // namespace
}  // namespace lockbox::net::rbtest
