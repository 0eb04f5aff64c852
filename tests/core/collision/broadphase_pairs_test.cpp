// b2BroadPhase pair contract: UpdatePairs reports the sorted, unique (min id, max id) pairs of
// the moved proxies' fat-AABB overlaps; the sequence is identical across runs, invariant under
// whole-metre shifts up to +-15,000 m, and pinned by a golden FNV-1a hash that every compiler
// and architecture must reproduce.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/BroadPhase.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using namespace lockbox::literals;

// Draw from it only in sequenced contexts (braced initialisers, separate statements): the
// evaluation order of function arguments differs between compilers.
class Rng {
public:
    explicit Rng(uint64_t seed) : m_state(seed) {}
    uint64_t Next() {
        uint64_t z = (m_state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    int64_t Range(int64_t lo, int64_t hi) {
        return lo + static_cast<int64_t>(Next() % static_cast<uint64_t>(hi - lo + 1));
    }
    Fixed Raw(int32_t lo, int32_t hi) { return Fixed::FromRaw(static_cast<int32_t>(Range(lo, hi))); }

private:
    uint64_t m_state;
};

using PairList = std::vector<std::pair<uint64, uint64>>;
constexpr uint64 kStepMark = ~uint64{0};

struct Recorder {
    PairList pairs;
    void AddPair(uint64 a, uint64 b) { pairs.emplace_back(a, b); }
};

/// FNV-1a 64 over the little-endian bytes of each value (independent of host byte order).
uint64 Fnv1a(const PairList& list) {
    uint64 h = 0xcbf29ce484222325ull;
    auto mix = [&h](uint64 v) {
        for (int i = 0; i < 8; ++i) {
            h ^= (v >> (8 * i)) & 0xFF;
            h *= 0x100000001b3ull;
        }
    };
    for (const auto& [a, b] : list) {
        mix(a);
        mix(b);
    }
    return h;
}

b2AABB Shifted(const b2AABB& b, const b2Vec2& s) { return b2AABB{b.lowerBound + s, b.upperBound + s}; }

/// The pairs UpdatePairs must report, by brute force: every moved proxy against every live one
/// (live maps proxy ids to their boxes), each distinct pair once in (id, id) order, as user data.
PairList BruteForcePairs(const b2BroadPhase& bp, const std::map<int32, b2AABB>& live) {
    std::vector<std::pair<int32, int32>> ids;
    for (const int32 q : bp.GetMoveBuffer()) {
        if (q == b2BroadPhase::e_nullProxy) continue;
        for (const auto& entry : live) {
            const int32 id = entry.first;
            if (id != q && bp.TestOverlap(q, id)) ids.emplace_back(std::min(q, id), std::max(q, id));
        }
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    PairList pairs;
    for (const auto& [a, b] : ids) pairs.emplace_back(bp.GetUserData(a), bp.GetUserData(b));
    return pairs;
}

/// How RunScenario takes a step's pairs: reported by UpdatePairs, or handed over by CollectPairs
/// (on one thread, or with the queries in blocks run last to first).
enum class Take { kUpdate, kCollect, kCollectInBlocks };

/// A seeded scene of boxes drifting in a 120 m square, with creations, destructions and
/// touches. Every step's UpdatePairs output (or CollectPairs's, as user data) is checked against
/// a brute-force scan and appended (followed by a step mark) to the returned sequence.
PairList RunScenario(const b2Vec2& shift, Take take = Take::kUpdate) {
    Rng rng(0xB0A0D5EEDull);
    b2BroadPhase bp;
    std::map<int32, b2AABB> live;  // proxy id -> unshifted tight box
    std::map<uint64, int32> idOf;  // user data -> proxy id
    uint64 nextUserData = 1000;
    PairList all;

    auto create = [&]() {
        const b2Vec2 c{rng.Raw(-60 * 65536, 60 * 65536), rng.Raw(-60 * 65536, 60 * 65536)};
        const b2Vec2 h{rng.Raw(6554, 98304), rng.Raw(6554, 98304)};
        const b2AABB box{c - h, c + h};
        const uint64 ud = nextUserData;
        nextUserData += 3;
        const int32 id = bp.CreateProxy(Shifted(box, shift), ud);
        live[id] = box;
        idOf[ud] = id;
    };
    auto pick = [&]() {
        auto it = live.begin();
        std::advance(it, static_cast<long>(rng.Range(0, static_cast<int64_t>(live.size()) - 1)));
        return it;
    };

    for (int i = 0; i < 400; ++i) create();
    for (int step = 0; step < 60; ++step) {
        for (int m = 0; m < 120; ++m) {
            auto it = pick();
            const b2Vec2 d{rng.Raw(-32768, 32768), rng.Raw(-32768, 32768)};
            it->second = b2AABB{it->second.lowerBound + d, it->second.upperBound + d};
            bp.MoveProxy(it->first, Shifted(it->second, shift), d);
        }
        for (int t = 0; t < 5; ++t) bp.TouchProxy(pick()->first);
        if (step % 7 == 3) {
            for (int k = 0; k < 4; ++k) {
                auto it = pick();
                bp.DestroyProxy(it->first);
                live.erase(it);
            }
            for (int k = 0; k < 4; ++k) create();
        }

        const PairList expected = BruteForcePairs(bp, live);

        Recorder rec;
        if (take == Take::kUpdate) {
            bp.UpdatePairs(&rec);
        } else {
            int32 blocksRun = 0;
            const auto lastToFirst = [&](int32 count, int32 blockSize, void (*range)(int32, int32, void*),
                                         void* context) {
                for (int32 k = (count - 1) / blockSize; k >= 0; --k, ++blocksRun)
                    range(k * blockSize, std::min((k + 1) * blockSize, count), context);
            };
            const bool inBlocks = take == Take::kCollectInBlocks;
            const auto moves = static_cast<int32>(bp.GetMoveBuffer().size());
            const std::vector<b2Pair>& pairs = inBlocks ? bp.CollectPairs(lastToFirst) : bp.CollectPairs();
            for (const b2Pair& pair : pairs) rec.AddPair(bp.GetUserData(pair.proxyIdA), bp.GetUserData(pair.proxyIdB));
            if (inBlocks) {
                // Every step moves more than one block's worth, so every step runs in blocks.
                EXPECT_GT(moves, b2BroadPhase::kMovesPerBlock);
                EXPECT_EQ(blocksRun, 1 + (moves - 1) / b2BroadPhase::kMovesPerBlock);
            }
        }
        EXPECT_EQ(rec.pairs, expected) << "step " << step;
        EXPECT_TRUE(bp.GetMoveBuffer().empty());
        EXPECT_EQ(bp.GetProxyCount(), static_cast<int32>(live.size()));
        EXPECT_TRUE(bp.GetTree().Validate());
        all.insert(all.end(), rec.pairs.begin(), rec.pairs.end());
        all.emplace_back(kStepMark, kStepMark);
    }
    return all;
}

// Golden value of RunScenario(0): pinned on x86-64 GCC; any compiler or architecture must give
// it too (the scenario uses integer arithmetic only).
constexpr uint64 kGoldenPairHash = 0xa640588c4d9a6c37ull;

TEST(BroadPhasePairs, MatchesBruteForceAndIsReproducible) {
    const PairList first = RunScenario(b2Vec2());
    const PairList second = RunScenario(b2Vec2());
    ASSERT_EQ(first, second);
    size_t pairs = 0;
    for (const auto& p : first) pairs += p.first != kStepMark;
    const uint64 hash = Fnv1a(first);
    std::printf("[broadphase] %zu pairs over 60 steps, FNV-1a 0x%016llx\n", pairs,
                static_cast<unsigned long long>(hash));
    EXPECT_GT(pairs, 1000u);
    EXPECT_EQ(hash, kGoldenPairHash);
}

// CollectPairs hands over what UpdatePairs reports, in the same order, each pair once, also
// when its queries run in blocks in another order.
TEST(BroadPhasePairs, CollectedPairsAreTheReportedOnes) {
    const PairList collected = RunScenario(b2Vec2(), Take::kCollect);
    EXPECT_EQ(Fnv1a(collected), kGoldenPairHash);
    EXPECT_EQ(collected, RunScenario(b2Vec2()));
    EXPECT_EQ(RunScenario(b2Vec2(), Take::kCollectInBlocks), collected);
}

TEST(BroadPhasePairs, ShiftedByWholeMetresGivesTheSamePairs) {
    const PairList base = RunScenario(b2Vec2());
    const b2Vec2 shifts[] = {{15000, 15000}, {-15000, -15000}, {15000, -15000}, {-15000, 15000}, {321, -9876}};
    for (const b2Vec2& s : shifts) {
        EXPECT_EQ(RunScenario(s), base) << "shift " << s.x.ToDouble() << ", " << s.y.ToDouble();
    }
}

// UpdatePairs sorts on the packed key: for every pair of non-negative ids (the tree's node
// indices) its order must be b2PairLessThan's, up to the largest id.
TEST(BroadPhasePairs, PackedKeyOrdersLikeThePairComparison) {
    Rng rng(77);
    const int32 edges[] = {0, 1, 2, 0x7FFF, 0x8000, 0xFFFF, 0x10000, 0x7FFFFFFE, 0x7FFFFFFF};
    std::vector<b2Pair> pairs;
    for (int32 a : edges)
        for (int32 b : edges) pairs.push_back(b2Pair{a, b});
    for (int i = 0; i < 2000; ++i) {
        const int32 a = static_cast<int32>(rng.Next() % 0x80000000u);
        const int32 b = static_cast<int32>(rng.Next() % (i % 2 == 0 ? 64u : 0x80000000u));
        pairs.push_back(b2Pair{a, b});
    }
    for (size_t i = 0; i < pairs.size(); ++i)
        for (size_t j = 0; j < pairs.size(); j += 7)
            ASSERT_EQ(PairKey(pairs[i]) < PairKey(pairs[j]), b2PairLessThan(pairs[i], pairs[j])) << i << " " << j;
}

// A crowded step reports hundreds of pairs, which are sorted by radix on a key packed at the ids'
// bit width instead of by comparison: the sequence must still be the brute-force one, also after
// destructions leave holes in the ids and creations reuse them.
TEST(BroadPhasePairs, CrowdedStepsGiveTheBruteForceSequence) {
    Rng rng(0xC20D);
    b2BroadPhase bp;
    std::map<int32, b2AABB> live;
    uint64 nextUserData = 7;
    auto create = [&]() {
        // Boxes of 0.5-3 m in a 40 m square: each overlaps about a dozen others.
        const b2Vec2 c{rng.Raw(-20 * 65536, 20 * 65536), rng.Raw(-20 * 65536, 20 * 65536)};
        const b2Vec2 h{rng.Raw(16384, 98304), rng.Raw(16384, 98304)};
        const int32 id = bp.CreateProxy(b2AABB{c - h, c + h}, nextUserData);
        nextUserData += 5;
        live[id] = b2AABB{c - h, c + h};
    };
    for (int i = 0; i < 1500; ++i) create();
    size_t fewest = SIZE_MAX;
    for (int step = 0; step < 6; ++step) {
        if (step > 0) {
            for (int k = 0; k < 300; ++k) {
                auto it = live.begin();
                std::advance(it, static_cast<long>(rng.Range(0, static_cast<int64_t>(live.size()) - 1)));
                if (k % 10 == 0) {
                    bp.DestroyProxy(it->first);
                    live.erase(it);
                    create();
                } else {
                    const b2Vec2 d{rng.Raw(-65536, 65536), rng.Raw(-65536, 65536)};
                    it->second = b2AABB{it->second.lowerBound + d, it->second.upperBound + d};
                    bp.MoveProxy(it->first, it->second, d);
                }
            }
        }
        const PairList expected = BruteForcePairs(bp, live);
        Recorder rec;
        bp.UpdatePairs(&rec);
        ASSERT_EQ(rec.pairs, expected) << "step " << step;
        fewest = std::min(fewest, expected.size());
    }
    // Every step is past the size from which the radix sort is taken.
    EXPECT_GT(fewest, 1000u);
}

TEST(BroadPhasePairs, SortedUniqueAndNoSelfPairs) {
    b2BroadPhase bp;
    // Five overlapping boxes created in an order that is not the id order of their pairs.
    std::vector<int32> ids;
    for (int i = 0; i < 5; ++i) ids.push_back(bp.CreateProxy(b2AABB{b2Vec2(i, 0), b2Vec2(i + 2, 1)}, 100 + i));
    bp.TouchProxy(ids[3]);  // duplicates in the move buffer
    bp.TouchProxy(ids[0]);
    ASSERT_EQ(bp.GetMoveBuffer().size(), 7u);
    Recorder rec;
    bp.UpdatePairs(&rec);
    // Boxes i and j overlap (touching counts) when |i - j| <= 2.
    const PairList expected = {{100, 101}, {100, 102}, {101, 102}, {101, 103}, {102, 103}, {102, 104}, {103, 104}};
    EXPECT_EQ(rec.pairs, expected);
    // Nothing moved: nothing to report.
    Recorder again;
    bp.UpdatePairs(&again);
    EXPECT_TRUE(again.pairs.empty());
}

TEST(BroadPhasePairs, DestroyAfterMoveAndTouchLeavesNoDanglingEntry) {
    b2BroadPhase bp;
    const int32 a = bp.CreateProxy(b2AABB{b2Vec2(-1, -1), b2Vec2(1, 1)}, 1);
    const int32 b = bp.CreateProxy(b2AABB{b2Vec2(5, 5), b2Vec2(6, 6)}, 2);
    Recorder warm;
    bp.UpdatePairs(&warm);
    EXPECT_TRUE(warm.pairs.empty());
    bp.MoveProxy(a, b2AABB{b2Vec2(4, 4), b2Vec2(6, 6)}, b2Vec2(5, 5));
    bp.TouchProxy(a);
    ASSERT_EQ(bp.GetMoveBuffer().size(), 2u);
    bp.DestroyProxy(a);
    for (const int32 id : bp.GetMoveBuffer()) EXPECT_EQ(id, b2BroadPhase::e_nullProxy);
    // Only the live pair (b, c) is reported; the destroyed proxy left nothing behind. c reuses
    // a's slot (the free-list head), so its id 0 is below b's and its user data comes first.
    const int32 c = bp.CreateProxy(b2AABB{b2Vec2(5.5_fx, 5.5_fx), b2Vec2(7, 7)}, 3);
    EXPECT_EQ(c, a);
    Recorder rec;
    bp.UpdatePairs(&rec);
    EXPECT_EQ(rec.pairs, (PairList{{3, 2}}));
    EXPECT_EQ(bp.GetProxyCount(), 2);
    EXPECT_TRUE(bp.TestOverlap(b, c));
}

TEST(BroadPhasePairs, NoAllocationOnceWarm) {
    // The buffers keep their capacity: a second identical step reports the same pairs.
    b2BroadPhase bp;
    std::vector<int32> ids;
    for (int i = 0; i < 64; ++i)
        ids.push_back(
            bp.CreateProxy(b2AABB{b2Vec2(i % 8, i / 8), b2Vec2(i % 8 + 1, i / 8 + 1)}, static_cast<uint64>(i)));
    Recorder r1;
    bp.UpdatePairs(&r1);
    for (const int32 id : ids) bp.TouchProxy(id);
    Recorder r2;
    bp.UpdatePairs(&r2);
    EXPECT_EQ(r1.pairs, r2.pairs);
    EXPECT_EQ(bp.GetTreeHeight(), bp.GetTree().GetHeight());
    EXPECT_LE(bp.GetTreeBalance(), 1);
    EXPECT_GT(bp.GetTreeQuality(), Wide(1));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
