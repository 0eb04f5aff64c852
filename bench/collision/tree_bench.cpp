// Dynamic tree: lockbox (Q16.16) against float Box2D 2.4.1 on the same scenes. Each scene is
// generated once as raw Q16.16 integers and converted exactly to float (raw / 65536 has at most
// 24 significant bits for |x| < 256 m), so both trees see the same boxes, motions and queries.
//
//   BM_<Op>_Lockbox / BM_<Op>_Box2D  for Op in Insert, Move, Query, RayCast.
// Compare the items_per_second of each pair; the report lists the ratios.
// lockbox first: float Box2D defines macros (b2_pi, b2_aabbExtension, b2_nullNode...) that
// would clash with lockbox's constants if its headers came first.
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "Box2DFloat.h"  // float Box2D without its constant macros
#include "lockbox/collision/DynamicTree.h"

namespace {

constexpr int kProxies = 1000;  // a busy scene
constexpr int kFrames = 64;     // motion frames, periodic
constexpr int kQueries = 256;
constexpr int kRays = 64;

class Rng {
public:
    explicit Rng(uint64_t seed) : m_state(seed) {}
    uint64_t Next() {
        uint64_t z = (m_state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    int32_t Range(int32_t lo, int32_t hi) {
        return lo + static_cast<int32_t>(Next() % static_cast<uint64_t>(int64_t{hi} - lo + 1));
    }

private:
    uint64_t m_state;
};

/// A box as raw Q16.16 bounds.
struct RawBox {
    int32_t lx, ly, ux, uy;
};

struct Scene {
    std::vector<RawBox> boxes;                // initial tight boxes
    std::vector<std::vector<RawBox>> frames;  // tight boxes per frame (periodic motion)
    std::vector<RawBox> queries;
    std::vector<RawBox> rays;  // p1 = (lx, ly), p2 = (ux, uy)
};

const Scene& GetScene() {
    static const Scene scene = [] {
        Scene s;
        Rng rng(7);
        std::vector<int32_t> vx, vy;
        for (int i = 0; i < kProxies; ++i) {
            const int32_t cx = rng.Range(-100 * 65536, 100 * 65536);
            const int32_t cy = rng.Range(-100 * 65536, 100 * 65536);
            const int32_t hx = rng.Range(16384, 65536);
            const int32_t hy = rng.Range(16384, 65536);
            s.boxes.push_back({cx - hx, cy - hy, cx + hx, cy + hy});
            vx.push_back(rng.Range(-6554, 6554));  // up to 0.1 m per frame
            vy.push_back(rng.Range(-6554, 6554));
        }
        // Triangle wave: move out for half the frames, back for the other half.
        for (int f = 0; f < kFrames; ++f) {
            const int k = f < kFrames / 2 ? f : kFrames - f;
            std::vector<RawBox> frame;
            for (int i = 0; i < kProxies; ++i) {
                const RawBox& b = s.boxes[static_cast<size_t>(i)];
                const int32_t dx = vx[static_cast<size_t>(i)] * k;
                const int32_t dy = vy[static_cast<size_t>(i)] * k;
                frame.push_back({b.lx + dx, b.ly + dy, b.ux + dx, b.uy + dy});
            }
            s.frames.push_back(frame);
        }
        for (int q = 0; q < kQueries; ++q) {
            const int32_t cx = rng.Range(-100 * 65536, 100 * 65536);
            const int32_t cy = rng.Range(-100 * 65536, 100 * 65536);
            s.queries.push_back({cx - 2 * 65536, cy - 2 * 65536, cx + 2 * 65536, cy + 2 * 65536});
        }
        for (int r = 0; r < kRays; ++r) {
            const int32_t x1 = rng.Range(-100 * 65536, 100 * 65536);
            const int32_t y1 = rng.Range(-100 * 65536, 100 * 65536);
            const int32_t x2 = rng.Range(-100 * 65536, 100 * 65536);
            const int32_t y2 = rng.Range(-100 * 65536, 100 * 65536);
            s.rays.push_back({x1, y1, x2, y2});
        }
        return s;
    }();
    return scene;
}

lockbox::b2AABB ToLockbox(const RawBox& b) {
    using lockbox::Fixed;
    return {{Fixed::FromRaw(b.lx), Fixed::FromRaw(b.ly)}, {Fixed::FromRaw(b.ux), Fixed::FromRaw(b.uy)}};
}
float RawToFloat(int32_t raw) { return static_cast<float>(raw) / 65536.0f; }
::b2AABB ToBox2D(const RawBox& b) {
    ::b2AABB a;
    a.lowerBound.Set(RawToFloat(b.lx), RawToFloat(b.ly));
    a.upperBound.Set(RawToFloat(b.ux), RawToFloat(b.uy));
    return a;
}

// ---- Insert -------------------------------------------------------------------------------

void BM_Insert_Lockbox(benchmark::State& state) {
    const Scene& s = GetScene();
    for (auto _ : state) {
        lockbox::b2DynamicTree tree;
        for (int i = 0; i < kProxies; ++i)
            tree.CreateProxy(ToLockbox(s.boxes[static_cast<size_t>(i)]), static_cast<uint64_t>(i));
        benchmark::DoNotOptimize(tree.GetRoot());
    }
    state.SetItemsProcessed(state.iterations() * kProxies);
}
void BM_Insert_Box2D(benchmark::State& state) {
    const Scene& s = GetScene();
    for (auto _ : state) {
        ::b2DynamicTree tree;
        for (int i = 0; i < kProxies; ++i) tree.CreateProxy(ToBox2D(s.boxes[static_cast<size_t>(i)]), nullptr);
        benchmark::DoNotOptimize(tree.GetHeight());
    }
    state.SetItemsProcessed(state.iterations() * kProxies);
}

// ---- Move ---------------------------------------------------------------------------------

void BM_Move_Lockbox(benchmark::State& state) {
    const Scene& s = GetScene();
    lockbox::b2DynamicTree tree;
    std::vector<int32_t> ids;
    for (int i = 0; i < kProxies; ++i) ids.push_back(tree.CreateProxy(ToLockbox(s.boxes[static_cast<size_t>(i)]), 0));
    int f = 0;
    int64_t reinserted = 0;
    for (auto _ : state) {
        const int next = (f + 1) % kFrames;
        const auto& from = s.frames[static_cast<size_t>(f)];
        const auto& to = s.frames[static_cast<size_t>(next)];
        for (int i = 0; i < kProxies; ++i) {
            const RawBox& a = from[static_cast<size_t>(i)];
            const RawBox& b = to[static_cast<size_t>(i)];
            const lockbox::b2Vec2 d(lockbox::Fixed::FromRaw(b.lx - a.lx), lockbox::Fixed::FromRaw(b.ly - a.ly));
            reinserted += tree.MoveProxy(ids[static_cast<size_t>(i)], ToLockbox(b), d);
        }
        f = next;
    }
    state.SetItemsProcessed(state.iterations() * kProxies);
    state.counters["reinserted/iter"] = static_cast<double>(reinserted) / static_cast<double>(state.iterations());
}
void BM_Move_Box2D(benchmark::State& state) {
    const Scene& s = GetScene();
    ::b2DynamicTree tree;
    std::vector<int32_t> ids;
    for (int i = 0; i < kProxies; ++i)
        ids.push_back(tree.CreateProxy(ToBox2D(s.boxes[static_cast<size_t>(i)]), nullptr));
    int f = 0;
    int64_t reinserted = 0;
    for (auto _ : state) {
        const int next = (f + 1) % kFrames;
        const auto& from = s.frames[static_cast<size_t>(f)];
        const auto& to = s.frames[static_cast<size_t>(next)];
        for (int i = 0; i < kProxies; ++i) {
            const RawBox& a = from[static_cast<size_t>(i)];
            const RawBox& b = to[static_cast<size_t>(i)];
            const ::b2Vec2 d(RawToFloat(b.lx - a.lx), RawToFloat(b.ly - a.ly));
            reinserted += tree.MoveProxy(ids[static_cast<size_t>(i)], ToBox2D(b), d);
        }
        f = next;
    }
    state.SetItemsProcessed(state.iterations() * kProxies);
    state.counters["reinserted/iter"] = static_cast<double>(reinserted) / static_cast<double>(state.iterations());
}

// ---- Query and RayCast --------------------------------------------------------------------

struct Counter {
    int64_t n = 0;
    bool QueryCallback(int32_t) {
        ++n;
        return true;
    }
    lockbox::Fixed RayCastCallback(const lockbox::b2RayCastInput& in, int32_t) {
        ++n;
        return in.maxFraction;
    }
    float RayCastCallback(const ::b2RayCastInput& in, int32_t) {
        ++n;
        return in.maxFraction;
    }
};

template <typename Tree, typename Convert>
void Fill(Tree& tree, Convert convert) {
    const Scene& s = GetScene();
    for (int i = 0; i < kProxies; ++i) tree.CreateProxy(convert(s.boxes[static_cast<size_t>(i)]), {});
}

void BM_Query_Lockbox(benchmark::State& state) {
    lockbox::b2DynamicTree tree;
    Fill(tree, ToLockbox);
    std::vector<lockbox::b2AABB> queries;
    for (const RawBox& q : GetScene().queries) queries.push_back(ToLockbox(q));
    Counter c;
    for (auto _ : state) {
        for (const auto& q : queries) tree.Query(&c, q);
    }
    state.SetItemsProcessed(state.iterations() * kQueries);
    state.counters["hits/query"] = static_cast<double>(c.n) / static_cast<double>(state.iterations() * kQueries);
}
void BM_Query_Box2D(benchmark::State& state) {
    ::b2DynamicTree tree;
    Fill(tree, ToBox2D);
    std::vector<::b2AABB> queries;
    for (const RawBox& q : GetScene().queries) queries.push_back(ToBox2D(q));
    Counter c;
    for (auto _ : state) {
        for (const auto& q : queries) tree.Query(&c, q);
    }
    state.SetItemsProcessed(state.iterations() * kQueries);
    state.counters["hits/query"] = static_cast<double>(c.n) / static_cast<double>(state.iterations() * kQueries);
}

void BM_RayCast_Lockbox(benchmark::State& state) {
    lockbox::b2DynamicTree tree;
    Fill(tree, ToLockbox);
    std::vector<lockbox::b2RayCastInput> rays;
    for (const RawBox& r : GetScene().rays) {
        const lockbox::b2AABB a = ToLockbox(r);
        rays.push_back({a.lowerBound, a.upperBound, lockbox::Fixed(1)});
    }
    Counter c;
    for (auto _ : state) {
        for (const auto& r : rays) tree.RayCast(&c, r);
    }
    state.SetItemsProcessed(state.iterations() * kRays);
    state.counters["hits/ray"] = static_cast<double>(c.n) / static_cast<double>(state.iterations() * kRays);
}
void BM_RayCast_Box2D(benchmark::State& state) {
    ::b2DynamicTree tree;
    Fill(tree, ToBox2D);
    std::vector<::b2RayCastInput> rays;
    for (const RawBox& r : GetScene().rays) {
        const ::b2AABB a = ToBox2D(r);
        ::b2RayCastInput in;
        in.p1 = a.lowerBound;
        in.p2 = a.upperBound;
        in.maxFraction = 1.0f;
        rays.push_back(in);
    }
    Counter c;
    for (auto _ : state) {
        for (const auto& r : rays) tree.RayCast(&c, r);
    }
    state.SetItemsProcessed(state.iterations() * kRays);
    state.counters["hits/ray"] = static_cast<double>(c.n) / static_cast<double>(state.iterations() * kRays);
}

BENCHMARK(BM_Insert_Lockbox);
BENCHMARK(BM_Insert_Box2D);
BENCHMARK(BM_Move_Lockbox);
BENCHMARK(BM_Move_Box2D);
BENCHMARK(BM_Query_Lockbox);
BENCHMARK(BM_Query_Box2D);
BENCHMARK(BM_RayCast_Lockbox);
BENCHMARK(BM_RayCast_Box2D);

}  // namespace

BENCHMARK_MAIN();
