// The start phase on real sockets at the start phase's promised spacing: on 127.0.0.1, two peers started 3 s
// apart, in either order, and a third started 1 s after the later of them, play the same match
// (about 15 s of wall time for both orders).

#include <chrono>

#include <gtest/gtest.h>

#include "../rollback_udp_start.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

TEST(RollbackUdpStart, PeersStartedSecondsApartAgree) {
    using std::chrono::seconds;
    for (uint32_t late = 0; late < 2; ++late) {
        SCOPED_TRACE(::testing::Message() << "late side " << late);
        UdpStartResult r;
        RunUdpStaggered(r, {late == 0 ? seconds(3) : seconds(0), late == 1 ? seconds(3) : seconds(0), seconds(4)}, 120);
        ExpectUdpStartedTogether(r, 120);
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
