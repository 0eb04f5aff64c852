// RollbackPeer::RemoteStats: every network figure of a remote in one call, checked against
// what the SimNet saw and what the sessions counted, and the loss estimate on clean and
// lossy links.

#include <cstdint>

#include <gtest/gtest.h>

#include "rollback_harness.h"

namespace lockbox::net::rbtest {
namespace LOCKBOX_TEST_FILE {

TEST(RollbackStats, OneCallPerRemoteMatchesTheNetwork) {
    RbSpec spec;
    spec.seed = 811;
    spec.rttMs = 100;
    spec.jitterMs = 10;
    spec.lossPct = 5;
    spec.frames = 360;
    const RbResult r = RunRbMatch(spec);
    ExpectHealthy(spec, r);
    for (uint32_t i = 0; i < 2; ++i) {
        SCOPED_TRACE(::testing::Message() << "peer " << i);
        const RbPeer& p = r.peers[i];
        const RollbackRemoteStats s = p.net->RemoteStats(0);
        const RollbackRemoteStats o = r.peers[1 - i].net->RemoteStats(0);
        EXPECT_TRUE(s.synchronized);
        EXPECT_TRUE(s.alive);
        EXPECT_FALSE(s.interrupted);
        // 100 ms of fixed latency plus up to 2 x 10 ms of jitter, plus up to a tick of holding.
        EXPECT_GE(s.rttMicros, 90000u);
        EXPECT_LE(s.rttMicros, 140000u);
        EXPECT_GT(s.rttSamples, 100u);
        // Everything this peer sent went to its one remote, headers counted as the SimNet does.
        EXPECT_EQ(r.wireBytesSent[i], s.bytesSent + SimNet::kWireOverhead * s.datagramsSent);
        // 5 % loss: the remote accepted a little less than was sent (some may be in flight).
        EXPECT_LE(o.datagramsReceived, s.datagramsSent);
        EXPECT_GE(o.datagramsReceived * 100, s.datagramsSent * 85);
        EXPECT_LE(o.bytesReceived, s.bytesSent);
        // The remote's estimate of our loss: 5 % on the link.
        EXPECT_GE(o.lossPermille, 25u);
        EXPECT_LE(o.lossPermille, 80u);
        EXPECT_GE(o.datagramsLost + o.datagramsReceived + 5, s.datagramsSent);
        // About 30 kbit/s up (docs/rollback.md's matrix), a little less arriving.
        EXPECT_GE(s.sendBitsPerSecond, 15000u);
        EXPECT_LE(s.sendBitsPerSecond, 64000u);
        EXPECT_GE(s.receiveBitsPerSecond, 12000u);
        EXPECT_LE(s.receiveBitsPerSecond, 64000u);
        // Time sync keeps the peers within a frame or two of each other.
        EXPECT_LE(s.framesAheadMilli, 3000);
        EXPECT_GE(s.framesAheadMilli, -3000);
        EXPECT_LE(s.remoteFramesAheadMilli, 3000);
        EXPECT_GE(s.remoteFramesAheadMilli, -3000);
        EXPECT_GT(s.remoteFrame, spec.frames - 60);
        // 50 ms one way against one frame of input delay: wrong guesses, each behind a rollback.
        const RollbackStats& own = p.session->Stats();
        EXPECT_EQ(s.rollbacks, own.rollbacks);
        EXPECT_EQ(s.framesResimulated, own.framesResimulated);
        EXPECT_EQ(s.deepestRollback, own.deepestRollback);
        EXPECT_GT(s.rollbacks, 0u);
        EXPECT_GE(s.mispredictedInputs, s.rollbacks);
        EXPECT_EQ(s.mispredictedInputs, p.session->MispredictedInputs(1 - i));
        EXPECT_EQ(p.session->MispredictedInputs(i), 0u);  // a local player is never guessed
    }
    const RollbackRemoteStats none = r.peers[0].net->RemoteStats(1);
    EXPECT_FALSE(none.alive);
    EXPECT_EQ(none.datagramsSent, 0u);
    EXPECT_EQ(none.lossPermille, 0u);
}

// No loss, then 20 %: the estimate follows the link.
TEST(RollbackStats, LossEstimateFollowsTheLink) {
    for (uint32_t loss : {0u, 20u}) {
        RbSpec spec;
        spec.seed = 812;
        spec.lossPct = loss;
        spec.frames = 240;
        const RbResult r = RunRbMatch(spec);
        ExpectHealthy(spec, r);
        for (const RbPeer& p : r.peers) {
            const RollbackRemoteStats s = p.net->RemoteStats(0);
            SCOPED_TRACE(::testing::Message() << "loss " << loss << "% estimate " << s.lossPermille);
            EXPECT_GE(s.lossPermille, loss * 10 * 7 / 10);
            EXPECT_LE(s.lossPermille, loss * 10 * 13 / 10 + 5);
        }
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net::rbtest
