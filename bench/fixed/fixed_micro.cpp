// fixed_micro: Google Benchmark micro-benchmarks of the fixed/ scalar math against the float
// (double for the Q32.32 rows) equivalents. Each iteration runs `acc += f(a[i])` over 4096
// precomputed inputs; items_per_second gives the per-op rate.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/Vec2.h"
#include "lockbox/fixed/Wide.h"

using lockbox::b2Vec2;
using lockbox::Fixed;
using lockbox::Wide;

namespace {

constexpr int kBatch = 4096;

struct Inputs {
    std::vector<int32_t> a, b;      // raw Q16.16, log-uniform magnitudes, random signs
    std::vector<int32_t> angles;    // raw angles within +-8 rad
    std::vector<int32_t> positive;  // raw values in [0, 2^31)
    std::vector<int64_t> wa, wb;    // raw Q32.32 operands with in-range products/quotients
    std::vector<float> fa, fb, fangles, fpositive;
    std::vector<double> da, db;

    Inputs() {
        std::mt19937_64 rng(12345);
        auto log_uniform = [&rng](int max_bits) {
            const int bits = static_cast<int>(rng() % static_cast<uint64_t>(max_bits));
            return static_cast<int64_t>((rng() >> (63 - bits)) | (uint64_t{1} << bits));
        };
        for (int i = 0; i < kBatch; ++i) {
            // Operands below 2^15 raw-bits each keep products and quotients mostly in range.
            const int32_t x = static_cast<int32_t>(log_uniform(24)) * ((rng() & 1) ? -1 : 1);
            const int32_t y = static_cast<int32_t>(log_uniform(24)) * ((rng() & 1) ? -1 : 1);
            a.push_back(x);
            b.push_back(y);
            fa.push_back(static_cast<float>(x) / 65536.0f);
            fb.push_back(static_cast<float>(y) / 65536.0f);
            const int32_t ang = static_cast<int32_t>(static_cast<int64_t>(rng() % 1048577) - 524288);
            angles.push_back(ang);
            fangles.push_back(static_cast<float>(ang) / 65536.0f);
            const int32_t p = static_cast<int32_t>(rng() >> 33);
            positive.push_back(p);
            fpositive.push_back(static_cast<float>(p) / 65536.0f);
            const int64_t u = log_uniform(46) * ((rng() & 1) ? -1 : 1);
            const int64_t v = log_uniform(46) + (int64_t{1} << 20);
            wa.push_back(u);
            wb.push_back(v);
            da.push_back(static_cast<double>(u) / 4294967296.0);
            db.push_back(static_cast<double>(v) / 4294967296.0);
        }
    }
};

const Inputs& In() {
    static const Inputs inputs;
    return inputs;
}

template <typename Acc, typename F>
void Run(benchmark::State& state, F f) {
    for (auto _ : state) {
        Acc acc{};
        for (int i = 0; i < kBatch; ++i) {
            int idx = i;
            benchmark::DoNotOptimize(idx);  // keeps the loop scalar, like the float baseline
            acc += f(idx);
        }
        benchmark::DoNotOptimize(acc);
    }
    state.SetItemsProcessed(state.iterations() * kBatch);
}

void BM_Mul_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) { return (Fixed::FromRaw(In().a[i]) * Fixed::FromRaw(In().b[i])).Raw(); });
}
void BM_Mul_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return In().fa[i] * In().fb[i]; });
}
void BM_Div_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) { return (Fixed::FromRaw(In().a[i]) / Fixed::FromRaw(In().b[i])).Raw(); });
}
void BM_Div_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return In().fa[i] / In().fb[i]; });
}
void BM_Sqrt_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) { return lockbox::math::Sqrt(Fixed::FromRaw(In().positive[i])).Raw(); });
}
void BM_Sqrt_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return std::sqrt(In().fpositive[i]); });
}
void BM_Sin_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) { return lockbox::math::Sin(Fixed::FromRaw(In().angles[i])).Raw(); });
}
void BM_Sin_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return std::sin(In().fangles[i]); });
}
void BM_Cos_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) { return lockbox::math::Cos(Fixed::FromRaw(In().angles[i])).Raw(); });
}
void BM_Cos_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return std::cos(In().fangles[i]); });
}
void BM_SinCos_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) {
        const lockbox::math::SinCosResult r = lockbox::math::SinCos(Fixed::FromRaw(In().angles[i]));
        return r.sin.Raw() + r.cos.Raw();
    });
}
void BM_SinCos_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return std::sin(In().fangles[i]) + std::cos(In().fangles[i]); });
}
void BM_Atan2_Fixed(benchmark::State& s) {
    Run<int32_t>(
        s, [](int i) { return lockbox::math::Atan2(Fixed::FromRaw(In().a[i]), Fixed::FromRaw(In().b[i])).Raw(); });
}
void BM_Atan2_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return std::atan2(In().fa[i], In().fb[i]); });
}
void BM_WrapAngle_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) { return lockbox::math::WrapAngle(Fixed::FromRaw(In().a[i] * 64)).Raw(); });
}
void BM_WrapAngle_Float(benchmark::State& s) {
    // Box2D-style float wrap: a - 2pi * floor((a + pi) / 2pi).
    Run<float>(s, [](int i) {
        const float x = In().fa[i] * 64.0f;
        return x - 6.28318531f * std::floor((x + 3.14159265f) / 6.28318531f);
    });
}
void BM_Length_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) { return b2Vec2(Fixed::FromRaw(In().a[i]), Fixed::FromRaw(In().b[i])).Length().Raw(); });
}
void BM_Length_Float(benchmark::State& s) {
    Run<float>(s, [](int i) { return std::hypot(In().fa[i], In().fb[i]); });
}
void BM_Normalize_Fixed(benchmark::State& s) {
    Run<int32_t>(s, [](int i) {
        b2Vec2 v(Fixed::FromRaw(In().a[i]), Fixed::FromRaw(In().b[i]));
        const Fixed len = v.Normalize();
        return v.x.Raw() + v.y.Raw() + len.Raw();
    });
}
void BM_Normalize_Float(benchmark::State& s) {
    Run<float>(s, [](int i) {
        const float x = In().fa[i], y = In().fb[i];
        const float len = std::sqrt(x * x + y * y);
        if (len < 1.1920929e-7f) return 0.0f;
        const float inv = 1.0f / len;
        return x * inv + y * inv + len;
    });
}
void BM_WideMul_Fixed(benchmark::State& s) {
    Run<int64_t>(s, [](int i) { return (Wide::FromRaw(In().wa[i]) * Wide::FromRaw(In().wb[i] >> 8)).Raw(); });
}
void BM_WideMul_Float(benchmark::State& s) {
    Run<double>(s, [](int i) { return In().da[i] * In().db[i]; });
}
void BM_WideDiv_Fixed(benchmark::State& s) {
    Run<int64_t>(s, [](int i) { return (Wide::FromRaw(In().wa[i]) / Wide::FromRaw(In().wb[i])).Raw(); });
}
void BM_WideDiv_Float(benchmark::State& s) {
    Run<double>(s, [](int i) { return In().da[i] / In().db[i]; });
}

}  // namespace

BENCHMARK(BM_Mul_Fixed);
BENCHMARK(BM_Mul_Float);
BENCHMARK(BM_Div_Fixed);
BENCHMARK(BM_Div_Float);
BENCHMARK(BM_Sqrt_Fixed);
BENCHMARK(BM_Sqrt_Float);
BENCHMARK(BM_Sin_Fixed);
BENCHMARK(BM_Sin_Float);
BENCHMARK(BM_Cos_Fixed);
BENCHMARK(BM_Cos_Float);
BENCHMARK(BM_SinCos_Fixed);
BENCHMARK(BM_SinCos_Float);
BENCHMARK(BM_Atan2_Fixed);
BENCHMARK(BM_Atan2_Float);
BENCHMARK(BM_WrapAngle_Fixed);
BENCHMARK(BM_WrapAngle_Float);
BENCHMARK(BM_Length_Fixed);
BENCHMARK(BM_Length_Float);
BENCHMARK(BM_Normalize_Fixed);
BENCHMARK(BM_Normalize_Float);
BENCHMARK(BM_WideMul_Fixed);
BENCHMARK(BM_WideMul_Float);
BENCHMARK(BM_WideDiv_Fixed);
BENCHMARK(BM_WideDiv_Float);

BENCHMARK_MAIN();
