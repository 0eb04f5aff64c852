// The chunked snapshot transfer of both late joins (net/src/SnapshotTransfer.h): a sender and
// a receiver on a hand-run link with a fixed one-way delay and seeded loss, one Pump per 60 Hz
// tick. The resend timer follows the round trip, so a receiver farther away than the
// configured timer no longer gets most chunks twice.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <vector>

#include "SnapshotTransfer.h"

namespace lockbox::net {
namespace {

constexpr uint64_t kTick = 16666;

struct TransferRun {
    uint64_t chunksSent = 0;
    uint64_t micros = 0;  ///< until the sender saw every ack
    bool complete = false;
    bool intact = false;
};

// `sampleRtt` false hands OnAck a zero clock, which never samples: the fixed-timer behaviour.
TransferRun Transfer(uint32_t chunks, uint64_t oneWayMicros, uint32_t lossPct, bool sampleRtt, uint64_t seed = 5) {
    std::vector<uint8_t> blob(size_t{chunks} * kSnapshotChunkBytes - 100);
    for (size_t i = 0; i < blob.size(); ++i) blob[i] = static_cast<uint8_t>(i * 31 + 7);
    SnapshotSender sender;
    sender.Start(42, blob);
    SnapshotReceiver receiver;
    struct InFlight {
        uint64_t at;
        SnapshotChunk chunk;
    };
    struct AckInFlight {
        uint64_t at;
        SnapshotAck ack;
    };
    std::deque<InFlight> toReceiver;
    std::deque<AckInFlight> toSender;
    uint64_t rng = seed;
    auto lost = [&] {
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        return (rng >> 33) % 100 < lossPct;
    };
    TransferRun out;
    for (uint64_t now = kTick; now < 60'000'000; now += kTick) {
        while (!toSender.empty() && toSender.front().at <= now) {
            sender.OnAck(toSender.front().ack, sampleRtt ? now : 0);
            toSender.pop_front();
        }
        if (sender.Done()) {
            out.micros = now;
            out.complete = true;
            break;
        }
        out.chunksSent += sender.Pump(now, 100000, 16, [&](const SnapshotChunk& c) {
            if (!lost()) toReceiver.push_back(InFlight{now + oneWayMicros, c});
        });
        while (!toReceiver.empty() && toReceiver.front().at <= now + kTick) {
            const InFlight f = toReceiver.front();
            toReceiver.pop_front();
            if (receiver.Accept(f.chunk) && !lost())
                toSender.push_back(AckInFlight{f.at + oneWayMicros, SnapshotAck{f.chunk.frame, f.chunk.index}});
        }
    }
    out.intact = receiver.Complete() && std::vector<uint8_t>(receiver.Blob().begin(), receiver.Blob().end()) == blob;
    return out;
}

TEST(SnapshotTransfer, ResendFollowsTheRoundTrip) {
    // 200 chunks at 150 ms RTT: 13 ticks to send them once, the first ack after 9.
    const TransferRun fixed = Transfer(200, 75000, 0, false);
    const TransferRun adaptive = Transfer(200, 75000, 0, true);
    ASSERT_TRUE(fixed.complete && fixed.intact);
    ASSERT_TRUE(adaptive.complete && adaptive.intact);
    std::printf("[ figures ] 200 chunks, 150 ms RTT, no loss: %llu sent with the 100 ms timer (%llu ms), %llu following "
                "the round trip (%llu ms)\n",
                static_cast<unsigned long long>(fixed.chunksSent), static_cast<unsigned long long>(fixed.micros / 1000),
                static_cast<unsigned long long>(adaptive.chunksSent), static_cast<unsigned long long>(adaptive.micros / 1000));
    // The fixed timer resends most chunks before their acks can come back.
    EXPECT_GE(fixed.chunksSent, 300u);
    // Only the chunks sent before the first ack returned go twice.
    EXPECT_LE(adaptive.chunksSent, 260u);
    EXPECT_LE(adaptive.micros, fixed.micros + 100000);
}

TEST(SnapshotTransfer, NearReceiverKeepsTheConfiguredTimer) {
    // 20 ms RTT: the round trip plus deviations stays under the 100 ms floor.
    const TransferRun adaptive = Transfer(200, 10000, 0, true);
    ASSERT_TRUE(adaptive.complete && adaptive.intact);
    EXPECT_EQ(adaptive.chunksSent, 200u);
}

TEST(SnapshotTransfer, LossyFarLinkStillCompletes) {
    for (uint64_t seed = 1; seed <= 5; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        const TransferRun fixed = Transfer(200, 75000, 20, false, seed);
        const TransferRun adaptive = Transfer(200, 75000, 20, true, seed);
        ASSERT_TRUE(adaptive.complete);
        EXPECT_TRUE(adaptive.intact);
        EXPECT_LT(adaptive.chunksSent, fixed.chunksSent);
        // Waiting for the round trip costs little time against resending at once.
        EXPECT_LE(adaptive.micros, fixed.micros + 600000);
        if (seed == 1)
            std::printf("[ figures ] 200 chunks, 150 ms RTT, 20 %% loss each way: %llu sent in %llu ms with the 100 ms "
                        "timer, %llu in %llu ms following the round trip\n",
                        static_cast<unsigned long long>(fixed.chunksSent), static_cast<unsigned long long>(fixed.micros / 1000),
                        static_cast<unsigned long long>(adaptive.chunksSent),
                        static_cast<unsigned long long>(adaptive.micros / 1000));
    }
}

TEST(SnapshotTransfer, ResendTimerHasFloorAndCeiling) {
    SnapshotSender s;
    EXPECT_EQ(s.ResendMicros(100000), 100000u);  // no sample yet
    s.Start(1, std::vector<uint8_t>(3 * kSnapshotChunkBytes, 1));
    s.Pump(10, 1, 16, [](const SnapshotChunk&) {});
    s.OnAck(SnapshotAck{1, 0}, 10 + 5'000'000);  // a 5 s round trip
    EXPECT_EQ(s.ResendMicros(100000), 1'000'000u);
    s.OnAck(SnapshotAck{1, 1}, 0);  // no clock: no sample, still acked
    s.OnAck(SnapshotAck{2, 2}, 20);  // another frame: ignored
    EXPECT_FALSE(s.Done());
    s.OnAck(SnapshotAck{1, 2}, 30);
    EXPECT_TRUE(s.Done());
}

}  // namespace
}  // namespace lockbox::net
