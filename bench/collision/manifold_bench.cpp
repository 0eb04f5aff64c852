// Manifold functions: lockbox (Q16.16) against float Box2D 2.4.1 on the same shape pairs.
// Pairs are generated once as raw Q16.16 values near contact and converted exactly to float, so
// both engines evaluate the same geometry. Compare the items_per_second of each
// BM_<Pair>_Lockbox / BM_<Pair>_Box2D pair (the main() is in tree_bench.cpp).
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "Box2DFloat.h"  // float Box2D without its constant macros
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"

namespace {

using lockbox::Fixed;

constexpr int kPairs = 256;

struct PairData {
    lockbox::b2Transform xfA, xfB;
    b2Transform fxfA, fxfB;
};

uint64_t Mix(uint64_t& s) {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Shape B placed within about a metre of shape A at a random angle: most pairs touch.
std::vector<PairData> MakePairs(uint64_t seed) {
    std::vector<PairData> pairs(kPairs);
    for (PairData& p : pairs) {
        const Fixed ax = Fixed::FromRaw(static_cast<int32_t>(Mix(seed) % 65536) - 32768);
        const Fixed bx = ax + Fixed::FromRaw(static_cast<int32_t>(Mix(seed) % 98304) - 49152);
        const Fixed by = Fixed::FromRaw(static_cast<int32_t>(Mix(seed) % 98304) - 32768);
        const Fixed angleA = Fixed::FromRaw(static_cast<int32_t>(Mix(seed) % 411775) - 205887);
        const Fixed angleB = Fixed::FromRaw(static_cast<int32_t>(Mix(seed) % 411775) - 205887);
        p.xfA.Set(lockbox::b2Vec2(ax, Fixed()), angleA);
        p.xfB.Set(lockbox::b2Vec2(bx, by), angleB);
        // Float transforms from the same rotation values, so both engines see the same frames.
        p.fxfA.p.Set(p.xfA.p.x.ToFloat(), p.xfA.p.y.ToFloat());
        p.fxfA.q.s = p.xfA.q.s.ToFloat();
        p.fxfA.q.c = p.xfA.q.c.ToFloat();
        p.fxfB.p.Set(p.xfB.p.x.ToFloat(), p.xfB.p.y.ToFloat());
        p.fxfB.q.s = p.xfB.q.s.ToFloat();
        p.fxfB.q.c = p.xfB.q.c.ToFloat();
    }
    return pairs;
}

struct Shapes {
    lockbox::b2CircleShape circle;
    lockbox::b2PolygonShape box;
    lockbox::b2EdgeShape edge;
    b2CircleShape fcircle;
    b2PolygonShape fbox;
    b2EdgeShape fedge;
    Shapes() {
        circle.SetRadius(Fixed(0.5));
        box.SetAsBox(Fixed(0.5), Fixed(0.25));
        edge.Set(lockbox::b2Vec2(Fixed(-2), Fixed()), lockbox::b2Vec2(Fixed(2), Fixed()));
        fcircle.m_radius = circle.m_radius.ToFloat();
        b2Vec2 v[lockbox::b2_maxPolygonVertices];
        for (int i = 0; i < box.m_vertexCount; ++i)
            v[i].Set(box.m_vertices[i].x.ToFloat(), box.m_vertices[i].y.ToFloat());
        fbox.Set(v, box.m_vertexCount);
        fbox.m_radius = box.m_radius.ToFloat();
        fedge.SetTwoSided(b2Vec2(-2.0f, 0.0f), b2Vec2(2.0f, 0.0f));
    }
};

const Shapes& TheShapes() {
    static const Shapes shapes;
    return shapes;
}
const std::vector<PairData>& ThePairs() {
    static const std::vector<PairData> pairs = MakePairs(42);
    return pairs;
}

template <typename F>
void Run(benchmark::State& state, F collide) {
    const auto& pairs = ThePairs();
    int touching = 0;
    for (auto _ : state) {
        for (const PairData& p : pairs) touching += collide(p);
    }
    benchmark::DoNotOptimize(touching);
    state.SetItemsProcessed(state.iterations() * kPairs);
}

void BM_Circles_Lockbox(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        lockbox::b2Manifold m;
        lockbox::b2CollideCircles(&m, &TheShapes().circle, p.xfA, &TheShapes().circle, p.xfB);
        return m.pointCount;
    });
}
void BM_Circles_Box2D(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        b2Manifold m;
        b2CollideCircles(&m, &TheShapes().fcircle, p.fxfA, &TheShapes().fcircle, p.fxfB);
        return m.pointCount;
    });
}
void BM_PolygonCircle_Lockbox(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        lockbox::b2Manifold m;
        lockbox::b2CollidePolygonAndCircle(&m, &TheShapes().box, p.xfA, &TheShapes().circle, p.xfB);
        return m.pointCount;
    });
}
void BM_PolygonCircle_Box2D(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        b2Manifold m;
        b2CollidePolygonAndCircle(&m, &TheShapes().fbox, p.fxfA, &TheShapes().fcircle, p.fxfB);
        return m.pointCount;
    });
}
void BM_Polygons_Lockbox(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        lockbox::b2Manifold m;
        lockbox::b2CollidePolygons(&m, &TheShapes().box, p.xfA, &TheShapes().box, p.xfB);
        return m.pointCount;
    });
}
void BM_Polygons_Box2D(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        b2Manifold m;
        b2CollidePolygons(&m, &TheShapes().fbox, p.fxfA, &TheShapes().fbox, p.fxfB);
        return m.pointCount;
    });
}
void BM_EdgeCircle_Lockbox(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        lockbox::b2Manifold m;
        lockbox::b2CollideEdgeAndCircle(&m, &TheShapes().edge, p.xfA, &TheShapes().circle, p.xfB);
        return m.pointCount;
    });
}
void BM_EdgeCircle_Box2D(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        b2Manifold m;
        b2CollideEdgeAndCircle(&m, &TheShapes().fedge, p.fxfA, &TheShapes().fcircle, p.fxfB);
        return m.pointCount;
    });
}
void BM_EdgePolygon_Lockbox(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        lockbox::b2Manifold m;
        lockbox::b2CollideEdgeAndPolygon(&m, &TheShapes().edge, p.xfA, &TheShapes().box, p.xfB);
        return m.pointCount;
    });
}
void BM_EdgePolygon_Box2D(benchmark::State& state) {
    Run(state, [](const PairData& p) {
        b2Manifold m;
        b2CollideEdgeAndPolygon(&m, &TheShapes().fedge, p.fxfA, &TheShapes().fbox, p.fxfB);
        return m.pointCount;
    });
}

}  // namespace

BENCHMARK(BM_Circles_Lockbox);
BENCHMARK(BM_Circles_Box2D);
BENCHMARK(BM_PolygonCircle_Lockbox);
BENCHMARK(BM_PolygonCircle_Box2D);
BENCHMARK(BM_Polygons_Lockbox);
BENCHMARK(BM_Polygons_Box2D);
BENCHMARK(BM_EdgeCircle_Lockbox);
BENCHMARK(BM_EdgeCircle_Box2D);
BENCHMARK(BM_EdgePolygon_Lockbox);
BENCHMARK(BM_EdgePolygon_Box2D);
