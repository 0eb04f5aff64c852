// Bad snapshot images: truncated, bit-flipped, foreign, wrong-version and structurally
// inconsistent images are refused with an error that names the problem, and the world they
// were offered to keeps its exact state (hash) and stays usable.

#include <cstring>

#include <gtest/gtest.h>

#include "StateTestUtil.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::SceneRun;

// A world with joints of several kinds, a gear, chains and contacts: pulley_gear after 20
// frames is the source; ragdolls after 5 frames is the world we try to overwrite.
struct Fixture {
    SceneRun source{"pulley_gear"};
    SceneRun target{"ragdolls"};
    std::vector<uint8> image;
    uint64 targetHash = 0;
    Fixture() {
        source.Advance(20);
        target.Advance(5);
        image = source.world().Save();
        targetHash = target.world().Hash();
    }
    /// Restores bytes into the target; checks the refusal leaves it untouched.
    b2RestoreResult Offer(const std::vector<uint8>& bytes) {
        const b2RestoreResult r = target.world().Restore(bytes);
        if (!r.ok()) {
            EXPECT_FALSE(r.message.empty());
            EXPECT_EQ(target.world().Hash(), targetHash) << "a refused restore changed the world: " << r.message;
        }
        return r;
    }
};

uint64 Rng(uint64& s) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return s >> 17;
}

TEST(SnapshotReject, EveryTruncationIsRefused) {
    Fixture fx;
    const size_t n = fx.image.size();
    for (size_t len = 0; len < n; len += (len < 200 ? 1 : 37)) {
        std::vector<uint8> cut(fx.image.begin(), fx.image.begin() + static_cast<std::ptrdiff_t>(len));
        const b2RestoreResult r = fx.Offer(cut);
        ASSERT_EQ(r.error, b2SnapshotError::e_truncated) << "length " << len << ": " << r.message;
    }
    // Trailing garbage is refused too.
    std::vector<uint8> longer = fx.image;
    longer.push_back(0);
    EXPECT_EQ(fx.Offer(longer).error, b2SnapshotError::e_trailingBytes);
}

TEST(SnapshotReject, EveryFlippedBitIsRefused) {
    Fixture fx;
    uint64 s = 42;
    for (int i = 0; i < 3000; ++i) {
        std::vector<uint8> bad = fx.image;
        const size_t at = i < 33 * 8 ? static_cast<size_t>(i / 8) : Rng(s) % bad.size();
        bad[at] ^= static_cast<uint8>(1u << (i < 33 * 8 ? i % 8 : Rng(s) % 8));
        const b2RestoreResult r = fx.Offer(bad);
        ASSERT_FALSE(r.ok()) << "flip at byte " << at << " was accepted";
    }
}

TEST(SnapshotReject, HeaderErrorsNameTheirField) {
    Fixture fx;
    auto edited = [&](size_t at, uint8 value) {
        std::vector<uint8> bad = fx.image;
        bad[at] = value;
        b2SealSnapshot(bad);
        return fx.Offer(bad);
    };
    EXPECT_EQ(edited(0, 0).error, b2SnapshotError::e_badEndianFlag);
    b2RestoreResult r = edited(1, 'X');
    EXPECT_EQ(r.error, b2SnapshotError::e_badMagic) << r.message;
    r = edited(5, 99);
    EXPECT_EQ(r.error, b2SnapshotError::e_badFormatVersion) << r.message;
    EXPECT_NE(r.message.find("format version 99"), std::string::npos) << r.message;
    r = edited(13, 0x7F);
    EXPECT_EQ(r.error, b2SnapshotError::e_badDeterminismVersion) << r.message;
    // An unsealed edit of the payload is a checksum error.
    std::vector<uint8> bad = fx.image;
    bad.back() ^= 1;
    EXPECT_EQ(fx.Offer(bad).error, b2SnapshotError::e_badChecksum);
    EXPECT_STREQ(b2SnapshotErrorName(b2SnapshotError::e_badChecksum), "bad checksum");
}

// Sealed random edits reach the structural checks: every image is either refused (world
// untouched) or restored into a world that can step without crashing or overflowing badly.
TEST(SnapshotReject, SealedCorruptionIsRefusedOrSafe) {
    Fixture fx;
    uint64 s = 7;
    int refused = 0, accepted = 0;
#ifdef NDEBUG
    constexpr int kTrials = 3000;
#else
    constexpr int kTrials = 600;
#endif
    for (int i = 0; i < kTrials; ++i) {
        std::vector<uint8> bad = fx.image;
        const int edits = 1 + static_cast<int>(Rng(s) % 4);
        for (int e = 0; e < edits; ++e) {
            const size_t at = 33 + Rng(s) % (bad.size() - 33);
            bad[at] = static_cast<uint8>(Rng(s) % 3 == 0 ? bad[at] ^ 0xFF : Rng(s));
        }
        b2SealSnapshot(bad);
        SceneRun scratch{"hello"};
        const uint64 before = scratch.world().Hash();
        const b2RestoreResult r = scratch.world().Restore(bad);
        if (!r.ok()) {
            ++refused;
            ASSERT_EQ(scratch.world().Hash(), before) << r.message;
        } else {
            ++accepted;
            // Accepted edits changed values, not structure: the world must keep working. The
            // values may be extreme (a corrupted mass), so checked builds would trap on the
            // resulting overflows: here they saturate as in release builds.
            const OverflowTrapHandler previous = SetOverflowTrapHandler([](const char*, int64_t, int64_t) {});
            for (int f = 0; f < 3; ++f) scratch.world().Step(Fixed::FromRatio(1, 60), 8, 3);
            SetOverflowTrapHandler(previous);
        }
    }
    EXPECT_GT(refused, kTrials / 4);
    std::printf("sealed corruption: %d refused, %d accepted and stepped\n", refused, accepted);
}

TEST(SnapshotReject, StructuralErrorsAreNamed) {
    Fixture fx;
    // Zeroing the whole payload after the header, sealed: the first section tag is wrong.
    std::vector<uint8> bad = fx.image;
    std::memset(bad.data() + 33, 0, bad.size() - 33);
    b2SealSnapshot(bad);
    const b2RestoreResult r = fx.Offer(bad);
    EXPECT_EQ(r.error, b2SnapshotError::e_corrupt);
    EXPECT_NE(r.message.find("settings"), std::string::npos) << r.message;
}

struct RestoreInsideStep : b2ContactListener {
    b2World* world = nullptr;
    std::vector<uint8> image;
    b2SnapshotError seen = b2SnapshotError::e_ok;
    void BeginContact(b2Contact*) override { seen = world->Restore(image).error; }
};

TEST(SnapshotReject, RestoreInsideStepIsRefused) {
    const b2AssertHandler previous = b2SetAssertHandler([](const char*, const char*, const char*, int) {});
    SceneRun run{"hello"};
    RestoreInsideStep listener;
    listener.world = &run.world();
    listener.image = run.world().Save();
    run.world().SetContactListener(&listener);
    for (int i = 0; i < 120 && listener.seen == b2SnapshotError::e_ok; ++i) run.Advance();
    EXPECT_EQ(listener.seen, b2SnapshotError::e_locked);
    b2SetAssertHandler(previous);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
