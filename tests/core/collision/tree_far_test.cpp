// Translation invariance and range: the same operations on boxes shifted by whole metres (up to
// +-15,000 m) build the same tree, and proxies at the corners of a +-16,000 m world with huge
// boxes never overflow (the checked build traps on any overflow; the default build counts
// saturations, which must stay at zero).
#include <cstdint>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/DynamicTree.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

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
    Fixed Metres(int32_t lo, int32_t hi) {
        return Fixed::FromRaw(static_cast<int32_t>(Range(int64_t{lo} * 65536, int64_t{hi} * 65536)));
    }

private:
    uint64_t m_state;
};

b2AABB Shifted(const b2AABB& b, const b2Vec2& s) { return b2AABB{b.lowerBound + s, b.upperBound + s}; }

struct RayHits {
    std::vector<int32> ids;
    Fixed RayCastCallback(const b2RayCastInput& in, int32 id) {
        ids.push_back(id);
        return in.maxFraction;
    }
};
struct QueryHits {
    std::vector<int32> ids;
    bool QueryCallback(int32 id) {
        ids.push_back(id);
        return true;
    }
};

/// Runs a seeded op sequence on a tree whose boxes are shifted by `shift`; also records the
/// ids (in callback order) of a few queries and ray casts after every batch.
b2DynamicTree RunShifted(const b2Vec2& shift, std::vector<int32>* callbackLog) {
    Rng rng(20261122);
    b2DynamicTree tree;
    std::map<int32, b2AABB> live;
    for (int op = 1; op <= 3000; ++op) {
        const int64_t r = rng.Range(0, 99);
        if (live.size() < 20 || (r < 40 && live.size() < 400)) {
            const b2Vec2 c{rng.Metres(-150, 150), rng.Metres(-150, 150)};
            const b2Vec2 h{Fixed::FromRaw(static_cast<int32_t>(rng.Range(3277, 4 * 65536))),
                           Fixed::FromRaw(static_cast<int32_t>(rng.Range(3277, 4 * 65536)))};
            const b2AABB box{c - h, c + h};
            live[tree.CreateProxy(Shifted(box, shift), static_cast<uint64>(op))] = box;
        } else if (r < 85) {
            auto it = live.begin();
            std::advance(it, static_cast<long>(rng.Range(0, static_cast<int64_t>(live.size()) - 1)));
            const b2Vec2 d{rng.Metres(-2, 2), rng.Metres(-2, 2)};
            it->second = b2AABB{it->second.lowerBound + d, it->second.upperBound + d};
            tree.MoveProxy(it->first, Shifted(it->second, shift), d);
        } else {
            auto it = live.begin();
            std::advance(it, static_cast<long>(rng.Range(0, static_cast<int64_t>(live.size()) - 1)));
            tree.DestroyProxy(it->first);
            live.erase(it);
        }
        if (op % 100 == 0) {
            EXPECT_TRUE(tree.Validate());
            const b2Vec2 q{rng.Metres(-150, 150), rng.Metres(-150, 150)};
            QueryHits qh;
            tree.Query(&qh, Shifted(b2AABB{q - b2Vec2(10, 10), q + b2Vec2(10, 10)}, shift));
            b2RayCastInput in;
            in.p1 = b2Vec2{rng.Metres(-150, 150), rng.Metres(-150, 150)} + shift;
            in.p2 = b2Vec2{rng.Metres(-150, 150), rng.Metres(-150, 150)} + shift;
            in.maxFraction = Fixed::FromRaw(static_cast<int32_t>(rng.Range(1, 65536)));
            RayHits rh;
            tree.RayCast(&rh, in);
            callbackLog->insert(callbackLog->end(), qh.ids.begin(), qh.ids.end());
            callbackLog->push_back(-2);
            callbackLog->insert(callbackLog->end(), rh.ids.begin(), rh.ids.end());
            callbackLog->push_back(-3);
        }
    }
    return tree;
}

TEST(TreeFar, ShiftByWholeMetresGivesTheSameTree) {
    std::vector<int32> baseLog;
    const b2DynamicTree base = RunShifted(b2Vec2(), &baseLog);
    const b2Vec2 shifts[] = {{15000, 15000}, {-15000, -15000}, {15000, -15000}, {-15000, 15000},
                             {-7777, 123},   {1, 0},           {0, -14999}};
    for (const b2Vec2& s : shifts) {
        std::vector<int32> log;
        const b2DynamicTree far = RunShifted(s, &log);
        ASSERT_EQ(log, baseLog) << "shift " << s.x.ToDouble() << ", " << s.y.ToDouble();
        ASSERT_EQ(far.GetRoot(), base.GetRoot());
        ASSERT_EQ(far.GetFreeList(), base.GetFreeList());
        ASSERT_EQ(far.GetNodeCount(), base.GetNodeCount());
        ASSERT_EQ(far.GetInsertionCount(), base.GetInsertionCount());
        ASSERT_EQ(far.GetAreaRatio(), base.GetAreaRatio());
        ASSERT_EQ(far.GetNodes().size(), base.GetNodes().size());
        for (size_t i = 0; i < base.GetNodes().size(); ++i) {
            const b2TreeNode& a = base.GetNodes()[i];
            b2TreeNode b = far.GetNodes()[i];
            if (b.height >= 0) b.aabb = Shifted(b.aabb, -s);  // free slots stay zeroed
            ASSERT_TRUE(a == b) << "node " << i;
        }
    }
}

TEST(TreeFar, WorldCornersWithHugeBoxesDoNotOverflow) {
    ResetSaturationCount();
    b2DynamicTree tree;
    const Fixed k = 16000;
    const Fixed big = 4000;
    std::vector<int32> ids;
    // Boxes at the four corners, a world-sized box, and long thin boxes along the borders.
    for (int sx = -1; sx <= 1; sx += 2) {
        for (int sy = -1; sy <= 1; sy += 2) {
            const b2Vec2 c(Fixed(sx) * k, Fixed(sy) * k);
            ids.push_back(tree.CreateProxy(b2AABB{c - b2Vec2(big, big), c + b2Vec2(big, big)}, 1));
            ids.push_back(tree.CreateProxy(b2AABB{c - b2Vec2(1, 1), c + b2Vec2(1, 1)}, 2));
        }
    }
    ids.push_back(tree.CreateProxy(b2AABB{b2Vec2(-k, -k), b2Vec2(k, k)}, 3));
    ids.push_back(tree.CreateProxy(b2AABB{b2Vec2(-k, -k), b2Vec2(k, -k + 1)}, 4));
    ids.push_back(tree.CreateProxy(b2AABB{b2Vec2(k - 1, -k), b2Vec2(k, k)}, 5));
    ASSERT_TRUE(tree.Validate());

    // Move the small corner boxes across the whole world in big jumps (the prediction doubles
    // a 16,000 m displacement to 32,000 m: the fat box clamps to the Fixed range).
    for (int step = 0; step < 8; ++step) {
        for (size_t i = 1; i < 8; i += 2) {
            const b2AABB& fat = tree.GetFatAABB(ids[i]);
            const b2Vec2 c = fat.GetCenter();
            const b2Vec2 d(c.x > Fixed() ? -k : k, c.y > Fixed() ? Fixed(-8000) : Fixed(8000));
            const b2Vec2 nc = b2Vec2(b2Clamp(c.x + d.x, -k, k), b2Clamp(c.y + d.y, -k, k));
            tree.MoveProxy(ids[i], b2AABB{nc - b2Vec2(1, 1), nc + b2Vec2(1, 1)}, d);
            ASSERT_TRUE(tree.Validate());
        }
    }
    // Full-diagonal ray (32,000 m long in each axis) and a world query.
    struct Count {
        int n = 0;
        Fixed RayCastCallback(const b2RayCastInput& in, int32) {
            ++n;
            return in.maxFraction;
        }
        bool QueryCallback(int32) {
            ++n;
            return true;
        }
    } ray, query;
    tree.RayCast(&ray, b2RayCastInput{b2Vec2(-k, -k), b2Vec2(k, k), Fixed(1)});
    tree.Query(&query, b2AABB{b2Vec2(-k, -k), b2Vec2(k, k)});
    EXPECT_GE(ray.n, 3);
    EXPECT_EQ(query.n, static_cast<int>(ids.size()));
    EXPECT_GT(tree.GetAreaRatio(), Wide(1));

    // Boxes at the very edge of the Fixed range: the extension clamps instead of overflowing.
    const Fixed edge = Fixed::FromRaw(Fixed::kMaxRaw);
    const int32 e = tree.CreateProxy(b2AABB{b2Vec2(-edge, -edge), b2Vec2(edge, edge)}, 6);
    EXPECT_EQ(tree.GetFatAABB(e).upperBound.x, edge);
    tree.MoveProxy(e, b2AABB{b2Vec2(-edge, -edge), b2Vec2(edge, edge)}, b2Vec2(edge, -edge));
    ASSERT_TRUE(tree.Validate());
    tree.RebuildBottomUp();
    ASSERT_TRUE(tree.Validate());
    EXPECT_EQ(SaturationCount(), 0u);
}

TEST(TreeFar, RayLineTestIsExactAtEveryScale) {
    // The separating-axis test has an int64 fast path and a 128-bit path; both must equal the
    // exact answer, from millimetre boxes to world-sized rays.
    __extension__ typedef __int128 i128;
    Rng rng(99);
    int misses = 0;
    for (int i = 0; i < 20000; ++i) {
        const int32_t scale = i % 4 == 0 ? 16000 : i % 4 == 1 ? 9000 : i % 4 == 2 ? 100 : 1;
        const b2Vec2 p1{rng.Metres(-scale, scale), rng.Metres(-scale, scale)};
        const b2Vec2 p2{rng.Metres(-scale, scale), rng.Metres(-scale, scale)};
        const b2Vec2 c{rng.Metres(-scale, scale), rng.Metres(-scale, scale)};
        const b2Vec2 h{Fixed::FromRaw(static_cast<int32_t>(rng.Range(0, int64_t{scale} * 16384))),
                       Fixed::FromRaw(static_cast<int32_t>(rng.Range(0, int64_t{scale} * 16384)))};
        const b2AABB box{c - h, c + h};
        const detail::b2TreeRay ray(p1, p2, Fixed(1));
        const i128 dx = i128{p2.x.Raw()} - p1.x.Raw();
        const i128 dy = i128{p2.y.Raw()} - p1.y.Raw();
        const i128 wx = 2 * i128{p1.x.Raw()} - box.lowerBound.x.Raw() - box.upperBound.x.Raw();
        const i128 wy = 2 * i128{p1.y.Raw()} - box.lowerBound.y.Raw() - box.upperBound.y.Raw();
        const i128 hx = i128{box.upperBound.x.Raw()} - box.lowerBound.x.Raw();
        const i128 hy = i128{box.upperBound.y.Raw()} - box.lowerBound.y.Raw();
        i128 sep = dx * wy - dy * wx;
        if (sep < 0) sep = -sep;
        const i128 reach = (dy < 0 ? -dy : dy) * hx + (dx < 0 ? -dx : dx) * hy;
        ASSERT_EQ(ray.LineMisses(box), sep > reach) << "case " << i;
        misses += sep > reach;
    }
    EXPECT_GT(misses, 1000);
    EXPECT_LT(misses, 19000);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
