// The chunked snapshot transfer of both late joins (net/src/SnapshotTransfer.h): a sender and
// a receiver on a hand-run link with a fixed one-way delay and seeded loss, one Pump per 60 Hz
// tick. The resend timer follows the round trip, so a receiver farther away than the
// configured timer no longer gets most chunks twice. Blobs travel zstd-compressed; the timer
// tests use random bytes, which do not compress, so their chunk counts are the blob's.

#include <cstdint>
#include <cstdio>
#include <deque>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/lockbox.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "session/SnapshotTransfer.h"

namespace lockbox::net {
namespace LOCKBOX_TEST_FILE {

constexpr uint64_t kTick = 16666;

std::vector<uint8_t> RandomBytes(size_t n, uint64_t seed) {
    std::vector<uint8_t> out(n);
    for (uint8_t& b : out) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        b = static_cast<uint8_t>(seed >> 56);
    }
    return out;
}

struct TransferRun {
    uint64_t chunksSent = 0;
    uint64_t micros = 0;  ///< until the sender saw every ack
    bool complete = false;
    bool intact = false;
};

// `sampleRtt` false hands OnAck a zero clock, which never samples: the fixed-timer behaviour.
TransferRun Transfer(uint32_t chunks, uint64_t oneWayMicros, uint32_t lossPct, bool sampleRtt, uint64_t seed = 5) {
    const std::vector<uint8_t> blob = RandomBytes(size_t{chunks} * kSnapshotChunkBytes - 100, 99);
    SnapshotSender sender;
    sender.Start(42, blob);
    EXPECT_EQ(sender.ChunkCount(), chunks);  // random bytes: the frame's few header bytes only
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
    std::printf(
        "[ figures ] 200 chunks, 150 ms RTT, no loss: %llu sent with the 100 ms timer (%llu ms), %llu following "
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
            std::printf(
                "[ figures ] 200 chunks, 150 ms RTT, 20 %% loss each way: %llu sent in %llu ms with the 100 ms "
                "timer, %llu in %llu ms following the round trip\n",
                static_cast<unsigned long long>(fixed.chunksSent), static_cast<unsigned long long>(fixed.micros / 1000),
                static_cast<unsigned long long>(adaptive.chunksSent),
                static_cast<unsigned long long>(adaptive.micros / 1000));
    }
}

TEST(SnapshotTransfer, ResendTimerHasFloorAndCeiling) {
    SnapshotSender s;
    EXPECT_EQ(s.ResendMicros(100000), 100000u);  // no sample yet
    s.Start(1, RandomBytes(3 * kSnapshotChunkBytes - 100, 3));
    ASSERT_EQ(s.ChunkCount(), 3u);
    s.Pump(10, 1, 16, [](const SnapshotChunk&) {});
    s.OnAck(SnapshotAck{1, 0}, 10 + 5'000'000);  // a 5 s round trip
    EXPECT_EQ(s.ResendMicros(100000), 1'000'000u);
    s.OnAck(SnapshotAck{1, 1}, 0);   // no clock: no sample, still acked
    s.OnAck(SnapshotAck{2, 2}, 20);  // another frame: ignored
    EXPECT_FALSE(s.Done());
    s.OnAck(SnapshotAck{1, 2}, 30);
    EXPECT_TRUE(s.Done());
}

// Collects every chunk of one snapshot, in order, each sent once.
std::vector<SnapshotChunk> AllChunks(SnapshotSender& sender) {
    std::vector<SnapshotChunk> out;
    sender.Pump(1, 100000, sender.ChunkCount(), [&](const SnapshotChunk& c) { out.push_back(c); });
    return out;
}

TEST(SnapshotTransfer, WorldImagesTravelCompressed) {
    // A world image after 120 steps of rain: the receiver hands out exactly the saved bytes,
    // which restore, from several times fewer chunks.
    auto scene = scenes::MakeLockboxScene("rain");
    scenes::LockboxEngine engine;
    scenes::ConfigureWorld(engine, scene->Info(), scenes::RunSettings{});
    scene->Prepare(scenes::Resolve(scene->Info(), scenes::RunSettings{}));
    scene->Build(engine);
    const auto& info = scene->Info();
    for (int f = 0; f < 120; ++f) {
        scene->BeforeStep(engine, f);
        engine.Step(info.hz, info.velocityIterations, info.positionIterations);
    }
    std::vector<uint8_t> image;
    engine.world().Save(image);
    const uint32_t plainChunks = static_cast<uint32_t>((image.size() + kSnapshotChunkBytes - 1) / kSnapshotChunkBytes);

    SnapshotSender sender;
    sender.Start(7, image);
    ASSERT_TRUE(sender.Active());
    std::printf("[ figures ] rain image after 120 steps: %zu bytes, %u chunks plain, %u compressed\n", image.size(),
                plainChunks, sender.ChunkCount());
    EXPECT_LE(sender.ChunkCount() * 3, plainChunks);

    SnapshotReceiver receiver;
    std::vector<SnapshotChunk> chunks = AllChunks(sender);
    ASSERT_EQ(chunks.size(), sender.ChunkCount());
    // Out of order, one repeated: still one snapshot, and the repeat is still acked.
    std::swap(chunks.front(), chunks.back());
    for (const SnapshotChunk& c : chunks) ASSERT_TRUE(receiver.Accept(c));
    ASSERT_TRUE(receiver.Complete());
    EXPECT_FALSE(receiver.Failed());
    EXPECT_TRUE(receiver.Accept(chunks[1]));
    ASSERT_EQ(std::vector<uint8_t>(receiver.Blob().begin(), receiver.Blob().end()), image);

    b2World copy(b2Vec2(Fixed(0), Fixed(0)));
    ASSERT_TRUE(copy.Restore(receiver.Blob()).ok());
    EXPECT_EQ(copy.Hash(), engine.world().Hash());
}

TEST(SnapshotTransfer, CorruptFrameFailsWithoutAHandOut) {
    const std::vector<uint8_t> plain(5000, 0x5A);
    SnapshotSender sender;
    sender.Start(3, plain);
    std::vector<SnapshotChunk> chunks = AllChunks(sender);
    ASSERT_EQ(chunks.size(), 1u);

    // A flipped byte in the frame header (its content size field), and a frame with trailing
    // bytes: both complete, neither hands out bytes.
    SnapshotChunk flipped = chunks[0];
    flipped.bytes[5] ^= 0xFF;
    SnapshotReceiver r1;
    ASSERT_TRUE(r1.Accept(flipped));
    EXPECT_TRUE(r1.Complete());
    EXPECT_TRUE(r1.Failed());
    EXPECT_TRUE(r1.Blob().empty());

    SnapshotChunk trailing = chunks[0];
    trailing.bytes.push_back(0);
    trailing.totalSize = static_cast<uint32_t>(trailing.bytes.size());
    SnapshotReceiver r2;
    ASSERT_TRUE(r2.Accept(trailing));
    EXPECT_TRUE(r2.Failed());
    EXPECT_TRUE(r2.Blob().empty());

    // Plain bytes that are no zstd frame at all.
    SnapshotReceiver r3;
    ASSERT_TRUE(r3.Accept(SnapshotChunk{4, 8, 0, std::vector<uint8_t>(8, 0x11)}));
    EXPECT_TRUE(r3.Failed());

    // A frame announcing more than the receiver accepts is refused before any allocation.
    SnapshotReceiver small(4096);
    ASSERT_TRUE(small.Accept(chunks[0]));
    EXPECT_TRUE(small.Failed());

    // Reset clears the failure; the intact frame then decompresses.
    r1.Reset();
    EXPECT_FALSE(r1.Failed());
    ASSERT_TRUE(r1.Accept(chunks[0]));
    EXPECT_FALSE(r1.Failed());
    EXPECT_EQ(std::vector<uint8_t>(r1.Blob().begin(), r1.Blob().end()), plain);
}

TEST(SnapshotTransfer, EmptyOrOversizedBlobIsNotSent) {
    SnapshotSender s;
    s.Start(1, std::span<const uint8_t>{});
    EXPECT_FALSE(s.Active());
    s.Start(1, std::vector<uint8_t>(size_t{kMaxSnapshotBytes} + 1, 0));
    EXPECT_FALSE(s.Active());
    EXPECT_EQ(s.ChunkCount(), 0u);
    EXPECT_EQ(SnapshotSender::Compress(std::span<const uint8_t>{}), nullptr);
    s.Start(1, CompressedSnapshot{});
    EXPECT_FALSE(s.Active());
}

// One compression shared by several senders (a late join offered to several joiners at once):
// each sends the chunks a sender of its own would, and each receiver gets the blob back; a
// sender that stops leaves the others' bytes intact.
TEST(SnapshotTransfer, SharedCompressionSendsTheSameChunks) {
    const std::vector<uint8_t> plain = RandomBytes(2 * kSnapshotChunkBytes, 11);
    std::vector<uint8_t> compressible(5 * kSnapshotChunkBytes);
    for (size_t i = 0; i < compressible.size(); ++i)
        compressible[i] = static_cast<uint8_t>(i % 7 == 0 ? plain[i % plain.size()] : 0);
    const CompressedSnapshot shared = SnapshotSender::Compress(compressible);
    ASSERT_NE(shared, nullptr);
    SnapshotSender own, a, b;
    own.Start(9, compressible);
    a.Start(9, shared);
    b.Start(9, shared);
    ASSERT_EQ(a.ChunkCount(), own.ChunkCount());
    ASSERT_LT(own.ChunkCount(), 5u);  // it did compress
    auto collect = [](SnapshotSender& s) {
        std::vector<SnapshotChunk> out;
        s.Pump(1, 100000, 64, [&](const SnapshotChunk& c) { out.push_back(c); });
        return out;
    };
    const std::vector<SnapshotChunk> ownChunks = collect(own);
    b.Stop();
    const std::vector<SnapshotChunk> aChunks = collect(a);
    ASSERT_EQ(aChunks.size(), ownChunks.size());
    SnapshotReceiver receiver;
    for (size_t i = 0; i < aChunks.size(); ++i) {
        EXPECT_EQ(aChunks[i].bytes, ownChunks[i].bytes);
        EXPECT_EQ(aChunks[i].totalSize, ownChunks[i].totalSize);
        EXPECT_TRUE(receiver.Accept(aChunks[i]));
    }
    ASSERT_TRUE(receiver.Complete());
    ASSERT_FALSE(receiver.Failed());
    EXPECT_EQ(std::vector<uint8_t>(receiver.Blob().begin(), receiver.Blob().end()), compressible);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::net
