// fixed_accuracy: accuracy and speed of the fixed/ math against long double references and the
// float (or double, for the Q32.32 rows) equivalents, as CSV:
//
//   function,inputs,max_ulp,mean_ulp,ns_fixed,ns_float
//
// Accuracy: max and mean absolute error in ULP of the output format (Q16.16: 2^-16; the wide_*
// rows: Q32.32, 2^-32) over `inputs` random inputs (fixed seeds). References are long double
// (x86-64: 64-bit mantissa), except wide_mul / wide_div, whose errors are computed exactly with
// 128-bit integer arithmetic made of 64-bit limbs.
// Speed: median over repetitions of ns per `acc += f(a[i])` over 4096 precomputed inputs; the
// float column runs the same loop with sqrtf, sinf, cosf, sinf + cosf, atan2f, float * and /,
// hypotf (length), a Box2D-style float normalize, and double * and / for the wide rows.
//
// Usage: fixed_accuracy [--quick] [--out FILE]
//   --quick     smaller samples and fewer repetitions
//   --out FILE  also write the CSV to FILE (e.g. bench/results/fixed_accuracy.csv)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/Vec2.h"
#include "lockbox/fixed/Wide.h"

using lockbox::b2Vec2;
using lockbox::Fixed;
using lockbox::Wide;

namespace {

constexpr int kBatch = 4096;
constexpr long double kQ16 = 65536.0L;
constexpr long double kQ32 = 4294967296.0L;

// ---- optimisation barriers ---------------------------------------------------------------------

// Makes the compiler forget what it knows about v (keeps loops scalar and results live).
template <typename T>
inline void Opaque(T& v) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    if constexpr (std::is_floating_point_v<T>) {
        asm volatile("" : "+x"(v));
    } else {
        asm volatile("" : "+r"(v));
    }
#elif defined(__GNUC__) && defined(__aarch64__)
    if constexpr (std::is_floating_point_v<T>) {
        asm volatile("" : "+w"(v));
    } else {
        asm volatile("" : "+r"(v));
    }
#elif defined(__GNUC__)
    asm volatile("" : "+m"(v));
#else
    volatile T sink = v;
    v = sink;
#endif
}

// Input pairs for the two-operand rows.
struct Pair32 {
    int32_t a, b;
};
struct FPair {
    float a, b;
};
struct Pair64 {
    int64_t a, b;
};
struct DPair {
    double a, b;
};

template <typename P>
inline void OpaquePair(P& p) {
    Opaque(p.a);
    Opaque(p.b);
}
inline void Opaque(Pair32& p) { OpaquePair(p); }
inline void Opaque(FPair& p) { OpaquePair(p); }
inline void Opaque(Pair64& p) { OpaquePair(p); }
inline void Opaque(DPair& p) { OpaquePair(p); }

// ---- error statistics --------------------------------------------------------------------------

struct ErrStats {
    long double max = 0;
    long double sum = 0;
    uint64_t count = 0;
    void Add(long double e) {
        e = std::fabs(e);
        if (e > max) max = e;
        sum += e;
        ++count;
    }
    long double Mean() const { return count ? sum / static_cast<long double>(count) : 0; }
};

// ---- exact 128-bit helpers for the wide rows (no __int128: this also builds on i686) ----------

struct U128 {
    uint64_t hi = 0, lo = 0;
};

U128 MulU64(uint64_t a, uint64_t b) {
    const uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
    U128 r;
    r.lo = (mid << 32) | (p00 & 0xFFFFFFFFu);
    r.hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    return r;
}

// Signed 128-bit value as sign and magnitude.
struct S128 {
    bool neg = false;
    U128 mag;
};

uint64_t AbsU64(int64_t v) { return v < 0 ? uint64_t{0} - static_cast<uint64_t>(v) : static_cast<uint64_t>(v); }

S128 MulS64(int64_t a, int64_t b) { return {(a < 0) != (b < 0), MulU64(AbsU64(a), AbsU64(b))}; }

S128 ShiftLeft32(int64_t a) {
    S128 r;
    r.neg = a < 0;
    const uint64_t m = AbsU64(a);
    r.mag.hi = m >> 32;
    r.mag.lo = m << 32;
    return r;
}

bool LessU128(const U128& a, const U128& b) { return a.hi != b.hi ? a.hi < b.hi : a.lo < b.lo; }

U128 SubU128(const U128& a, const U128& b) {  // a >= b
    U128 r;
    r.lo = a.lo - b.lo;
    r.hi = a.hi - b.hi - (a.lo < b.lo ? 1 : 0);
    return r;
}

// |a - b| as long double.
long double AbsDiff(const S128& a, const S128& b) {
    U128 m;
    if (a.neg == b.neg) {
        m = LessU128(a.mag, b.mag) ? SubU128(b.mag, a.mag) : SubU128(a.mag, b.mag);
    } else {
        m.lo = a.mag.lo + b.mag.lo;
        m.hi = a.mag.hi + b.mag.hi + (m.lo < a.mag.lo ? 1 : 0);
    }
    return static_cast<long double>(m.hi) * 18446744073709551616.0L + static_cast<long double>(m.lo);
}

// ---- timing ------------------------------------------------------------------------------------

struct TimingConfig {
    int reps = 15;
    int inner = 40;  // passes over the 4096 inputs per repetition
};

// Median ns per element of body() (which processes kBatch elements once).
double MedianNs(const TimingConfig& cfg, const std::function<void()>& body) {
    body();  // warm-up
    std::vector<double> samples;
    for (int r = 0; r < cfg.reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < cfg.inner; ++i) body();
        const auto t1 = std::chrono::steady_clock::now();
        samples.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() /
                          (static_cast<double>(cfg.inner) * kBatch));
    }
    std::sort(samples.begin(), samples.end());
    return samples[samples.size() / 2];
}

// Times `acc += f(a[i])` for i over the batch; F maps an input element to a value added to acc.
template <typename Acc, typename In, typename F>
double TimeLoop(const TimingConfig& cfg, const std::vector<In>& in, F f) {
    return MedianNs(cfg, [&] {
        Acc acc{};
        for (int i = 0; i < kBatch; ++i) {
            In v = in[static_cast<size_t>(i)];
            Opaque(v);
            acc += f(v);
        }
        Opaque(acc);
    });
}

// ---- input generators --------------------------------------------------------------------------

// Log-uniform magnitude in [1, 2^maxBits) (clamped to max), random sign when signed.
int64_t LogUniform(std::mt19937_64& rng, int maxBits, int64_t max, bool allow_negative) {
    const int bits = static_cast<int>(rng() % static_cast<uint64_t>(maxBits));
    int64_t v = static_cast<int64_t>((rng() >> (63 - bits)) | (uint64_t{1} << bits));
    if (v > max) v = max;
    if (allow_negative && (rng() & 1)) v = -v;
    return v;
}

int32_t LogUniformRaw(std::mt19937_64& rng) { return static_cast<int32_t>(LogUniform(rng, 31, 2147483647, true)); }

// ---- the rows ----------------------------------------------------------------------------------

struct Row {
    std::string function;
    uint64_t inputs;
    long double max_ulp, mean_ulp;
    double ns_fixed, ns_float;
};

float ToF(int32_t raw) { return static_cast<float>(raw) / 65536.0f; }

Row MulRow(int n, const TimingConfig& cfg) {
    std::mt19937_64 rng(1);
    ErrStats st;
    std::vector<Pair32> in;
    while (static_cast<int>(st.count) < n) {
        const int32_t a = LogUniformRaw(rng), b = LogUniformRaw(rng);
        const long double exact = static_cast<long double>(a) * b / kQ16;  // exact in 64-bit mantissa
        if (std::fabs(exact) >= 2147483647.0L) continue;
        const Fixed r = Fixed::FromRaw(a) * Fixed::FromRaw(b);
        st.Add(r.Raw() - exact);
        if (in.size() < kBatch) in.push_back({a, b});
    }
    std::vector<FPair> fin;
    for (const Pair32& p : in) fin.push_back({ToF(p.a), ToF(p.b)});
    const double nf =
        TimeLoop<int32_t>(cfg, in, [](Pair32 p) { return (Fixed::FromRaw(p.a) * Fixed::FromRaw(p.b)).Raw(); });
    const double ff = TimeLoop<float>(cfg, fin, [](FPair p) { return p.a * p.b; });
    return {"mul", st.count, st.max, st.Mean(), nf, ff};
}

Row DivRow(int n, const TimingConfig& cfg) {
    std::mt19937_64 rng(2);
    ErrStats st;
    std::vector<Pair32> in;
    while (static_cast<int>(st.count) < n) {
        const int32_t a = LogUniformRaw(rng), b = LogUniformRaw(rng);
        const long double exact = static_cast<long double>(a) * kQ16 / b;
        if (std::fabs(exact) >= 2147483647.0L) continue;
        const Fixed r = Fixed::FromRaw(a) / Fixed::FromRaw(b);
        st.Add(r.Raw() - exact);
        if (in.size() < kBatch) in.push_back({a, b});
    }
    std::vector<FPair> fin;
    for (const Pair32& p : in) fin.push_back({ToF(p.a), ToF(p.b)});
    const double nf =
        TimeLoop<int32_t>(cfg, in, [](Pair32 p) { return (Fixed::FromRaw(p.a) / Fixed::FromRaw(p.b)).Raw(); });
    const double ff = TimeLoop<float>(cfg, fin, [](FPair p) { return p.a / p.b; });
    return {"div", st.count, st.max, st.Mean(), nf, ff};
}

Row SqrtRow(int n, const TimingConfig& cfg) {
    std::mt19937_64 rng(3);
    ErrStats st;
    std::vector<int32_t> in;
    for (int i = 0; i < n; ++i) {
        // Half uniform raws, half log-uniform (small values matter for lengths).
        const int32_t x =
            (i & 1) ? static_cast<int32_t>(rng() >> 33) : static_cast<int32_t>(LogUniform(rng, 31, 2147483647, false));
        const int32_t r = lockbox::math::Sqrt(Fixed::FromRaw(x)).Raw();
        st.Add(r - std::sqrt(static_cast<long double>(x) * kQ16));
        if (in.size() < kBatch) in.push_back(x);
    }
    std::vector<float> fin;
    for (int32_t x : in) fin.push_back(ToF(x));
    const double nf =
        TimeLoop<int32_t>(cfg, in, [](int32_t x) { return lockbox::math::Sqrt(Fixed::FromRaw(x)).Raw(); });
    const double ff = TimeLoop<float>(cfg, fin, [](float x) { return std::sqrt(x); });
    return {"sqrt", st.count, st.max, st.Mean(), nf, ff};
}

// Angles: half uniform over the whole int32 range, half uniform over [-4pi, 4pi].
std::vector<int32_t> Angles(int n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<int32_t> v(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        v[static_cast<size_t>(i)] = (i & 1) ? static_cast<int32_t>(static_cast<uint32_t>(rng()))
                                            : static_cast<int32_t>(static_cast<int64_t>(rng() % 1647101) - 823550);
    }
    return v;
}

std::vector<int32_t> TimingAngles() {
    // Timing inputs within +-8 rad, where sinf/cosf take their fast path.
    std::mt19937_64 rng(44);
    std::vector<int32_t> v;
    for (int i = 0; i < kBatch; ++i) v.push_back(static_cast<int32_t>(static_cast<int64_t>(rng() % 1048577) - 524288));
    return v;
}

Row SinCosRows(int n, const TimingConfig& cfg, Row* sin_row, Row* cos_row) {
    const std::vector<int32_t> angles = Angles(n, 4);
    ErrStats ss, cs, both;
    for (int32_t x : angles) {
        const lockbox::math::SinCosResult r = lockbox::math::SinCos(Fixed::FromRaw(x));
        const long double a = static_cast<long double>(x) / kQ16;
        const long double es = r.sin.Raw() - std::sin(a) * kQ16;
        const long double ec = r.cos.Raw() - std::cos(a) * kQ16;
        ss.Add(es);
        cs.Add(ec);
        both.Add(es);
        both.Add(ec);
    }
    const std::vector<int32_t> in = TimingAngles();
    std::vector<float> fin;
    for (int32_t x : in) fin.push_back(ToF(x));
    const double n_sin =
        TimeLoop<int32_t>(cfg, in, [](int32_t x) { return lockbox::math::Sin(Fixed::FromRaw(x)).Raw(); });
    const double f_sin = TimeLoop<float>(cfg, fin, [](float x) { return std::sin(x); });
    const double n_cos =
        TimeLoop<int32_t>(cfg, in, [](int32_t x) { return lockbox::math::Cos(Fixed::FromRaw(x)).Raw(); });
    const double f_cos = TimeLoop<float>(cfg, fin, [](float x) { return std::cos(x); });
    const double n_sc = TimeLoop<int32_t>(cfg, in, [](int32_t x) {
        const lockbox::math::SinCosResult r = lockbox::math::SinCos(Fixed::FromRaw(x));
        return r.sin.Raw() + r.cos.Raw();
    });
    const double f_sc = TimeLoop<float>(cfg, fin, [](float x) { return std::sin(x) + std::cos(x); });
    *sin_row = {"sin", ss.count, ss.max, ss.Mean(), n_sin, f_sin};
    *cos_row = {"cos", cs.count, cs.max, cs.Mean(), n_cos, f_cos};
    return {"sincos", static_cast<uint64_t>(n), both.max, both.Mean(), n_sc, f_sc};
}

Row Atan2Row(int n, const TimingConfig& cfg) {
    std::mt19937_64 rng(5);
    ErrStats st;
    std::vector<Pair32> in;
    for (int i = 0; i < n; ++i) {
        const int32_t y = LogUniformRaw(rng), x = LogUniformRaw(rng);
        const int32_t r = lockbox::math::Atan2(Fixed::FromRaw(y), Fixed::FromRaw(x)).Raw();
        st.Add(r - std::atan2(static_cast<long double>(y), static_cast<long double>(x)) * kQ16);
        if (in.size() < kBatch) in.push_back({y, x});
    }
    std::vector<FPair> fin;
    for (const Pair32& p : in) fin.push_back({ToF(p.a), ToF(p.b)});
    const double nf = TimeLoop<int32_t>(
        cfg, in, [](Pair32 p) { return lockbox::math::Atan2(Fixed::FromRaw(p.a), Fixed::FromRaw(p.b)).Raw(); });
    const double ff = TimeLoop<float>(cfg, fin, [](FPair p) { return std::atan2(p.a, p.b); });
    return {"atan2", st.count, st.max, st.Mean(), nf, ff};
}

// Vectors with log-uniform length in [2^-16, 2^14] m (so that the length fits Q16.16) and a
// uniform direction.
std::vector<Pair32> Vectors(int n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<long double> dir(0, 6.283185307179586476925L);
    std::uniform_real_distribution<long double> lg(0, 30);
    std::vector<Pair32> v;
    while (static_cast<int>(v.size()) < n) {
        const long double len = std::pow(2.0L, lg(rng));  // raw units
        const long double th = dir(rng);
        const int32_t x = static_cast<int32_t>(std::llround(len * std::cos(th)));
        const int32_t y = static_cast<int32_t>(std::llround(len * std::sin(th)));
        if (x == 0 && y == 0) continue;
        v.push_back({x, y});
    }
    return v;
}

Row LengthRow(int n, const TimingConfig& cfg) {
    const std::vector<Pair32> vs = Vectors(n, 6);
    ErrStats st;
    for (const Pair32& p : vs) {
        const b2Vec2 v(Fixed::FromRaw(p.a), Fixed::FromRaw(p.b));
        const long double exact = std::sqrt(static_cast<long double>(p.a) * p.a + static_cast<long double>(p.b) * p.b);
        st.Add(v.Length().Raw() - exact);
    }
    const std::vector<Pair32> in(vs.begin(), vs.begin() + std::min<size_t>(kBatch, vs.size()));
    std::vector<FPair> fin;
    for (const Pair32& p : in) fin.push_back({ToF(p.a), ToF(p.b)});
    const double nf = TimeLoop<int32_t>(
        cfg, in, [](Pair32 p) { return b2Vec2(Fixed::FromRaw(p.a), Fixed::FromRaw(p.b)).Length().Raw(); });
    const double ff = TimeLoop<float>(cfg, fin, [](FPair p) { return std::hypot(p.a, p.b); });
    return {"length", st.count, st.max, st.Mean(), nf, ff};
}

Row NormalizeRow(int n, const TimingConfig& cfg) {
    const std::vector<Pair32> vs = Vectors(n, 7);
    ErrStats st;  // per component, in Q16.16 ULP of the unit vector
    for (const Pair32& p : vs) {
        b2Vec2 v(Fixed::FromRaw(p.a), Fixed::FromRaw(p.b));
        v.Normalize();
        const long double len = std::sqrt(static_cast<long double>(p.a) * p.a + static_cast<long double>(p.b) * p.b);
        st.Add(v.x.Raw() - p.a / len * kQ16);
        st.Add(v.y.Raw() - p.b / len * kQ16);
    }
    const std::vector<Pair32> in(vs.begin(), vs.begin() + std::min<size_t>(kBatch, vs.size()));
    std::vector<FPair> fin;
    for (const Pair32& p : in) fin.push_back({ToF(p.a), ToF(p.b)});
    const double nf = TimeLoop<int32_t>(cfg, in, [](Pair32 p) {
        b2Vec2 v(Fixed::FromRaw(p.a), Fixed::FromRaw(p.b));
        const Fixed len = v.Normalize();
        return v.x.Raw() + v.y.Raw() + len.Raw();
    });
    const double ff = TimeLoop<float>(cfg, fin, [](FPair p) {
        // Box2D 2.2.1 b2Vec2::Normalize in float.
        const float len = std::sqrt(p.a * p.a + p.b * p.b);
        if (len < 1.1920929e-7f) return 0.0f;
        const float inv = 1.0f / len;
        return p.a * inv + p.b * inv + len;
    });
    return {"normalize", st.count, st.max, st.Mean(), nf, ff};
}

Row WideMulRow(int n, const TimingConfig& cfg) {
    std::mt19937_64 rng(8);
    ErrStats st;
    std::vector<Pair64> in;
    while (static_cast<int>(st.count) < n) {
        // |a * b| / 2^32 < 2^62: bit lengths with ea + eb <= 93.
        const int64_t a = LogUniform(rng, 62, INT64_MAX, true);
        const int64_t b = LogUniform(rng, 62, INT64_MAX, true);
        const long double approx = static_cast<long double>(a) * static_cast<long double>(b) / kQ32;
        if (std::fabs(approx) >= 4.0e18L) continue;
        const int64_t r = (Wide::FromRaw(a) * Wide::FromRaw(b)).Raw();
        // Error in Q32.32 ULP: |r * 2^32 - a * b| / 2^32, exactly.
        st.Add(AbsDiff(ShiftLeft32(r), MulS64(a, b)) / kQ32);
        if (in.size() < kBatch) in.push_back({a, b});
    }
    std::vector<DPair> din;
    for (const Pair64& p : in)
        din.push_back({static_cast<double>(p.a) / 4294967296.0, static_cast<double>(p.b) / 4294967296.0});
    const double nf =
        TimeLoop<int64_t>(cfg, in, [](Pair64 p) { return (Wide::FromRaw(p.a) * Wide::FromRaw(p.b)).Raw(); });
    const double ff = TimeLoop<double>(cfg, din, [](DPair p) { return p.a * p.b; });
    return {"wide_mul", st.count, st.max, st.Mean(), nf, ff};
}

Row WideDivRow(int n, const TimingConfig& cfg) {
    std::mt19937_64 rng(9);
    ErrStats st;
    std::vector<Pair64> in;
    while (static_cast<int>(st.count) < n) {
        const int64_t a = LogUniform(rng, 62, INT64_MAX, true);
        const int64_t b = LogUniform(rng, 62, INT64_MAX, true);
        const long double approx = static_cast<long double>(a) * kQ32 / static_cast<long double>(b);
        if (std::fabs(approx) >= 4.0e18L) continue;
        const int64_t r = (Wide::FromRaw(a) / Wide::FromRaw(b)).Raw();
        // Error in Q32.32 ULP: |r * b - a * 2^32| / |b|, exactly up to the final division.
        st.Add(AbsDiff(MulS64(r, b), ShiftLeft32(a)) / static_cast<long double>(AbsU64(b)));
        if (in.size() < kBatch) in.push_back({a, b});
    }
    std::vector<DPair> din;
    for (const Pair64& p : in)
        din.push_back({static_cast<double>(p.a) / 4294967296.0, static_cast<double>(p.b) / 4294967296.0});
    const double nf =
        TimeLoop<int64_t>(cfg, in, [](Pair64 p) { return (Wide::FromRaw(p.a) / Wide::FromRaw(p.b)).Raw(); });
    const double ff = TimeLoop<double>(cfg, din, [](DPair p) { return p.a / p.b; });
    return {"wide_div", st.count, st.max, st.Mean(), nf, ff};
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false;
    const char* out_path = nullptr;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
        } else if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
            out_path = argv[++i];
        } else {
            std::fprintf(stderr, "usage: %s [--quick] [--out FILE]\n", argv[0]);
            return 2;
        }
    }
    const int n = quick ? 100000 : 2000000;
    TimingConfig cfg;
    if (quick) {
        cfg.reps = 5;
        cfg.inner = 10;
    }

    std::vector<Row> rows;
    rows.push_back(MulRow(n, cfg));
    rows.push_back(DivRow(n, cfg));
    rows.push_back(SqrtRow(n, cfg));
    Row sin_row, cos_row;
    const Row sincos_row = SinCosRows(n, cfg, &sin_row, &cos_row);
    rows.push_back(sin_row);
    rows.push_back(cos_row);
    rows.push_back(sincos_row);
    rows.push_back(Atan2Row(n, cfg));
    rows.push_back(LengthRow(n, cfg));
    rows.push_back(NormalizeRow(n, cfg));
    rows.push_back(WideMulRow(n, cfg));
    rows.push_back(WideDivRow(n, cfg));

    std::string csv = "function,inputs,max_ulp,mean_ulp,ns_fixed,ns_float\n";
    for (const Row& r : rows) {
        char line[256];
        std::snprintf(line, sizeof line, "%s,%llu,%.6Lf,%.6Lf,%.3f,%.3f\n", r.function.c_str(),
                      static_cast<unsigned long long>(r.inputs), r.max_ulp, r.mean_ulp, r.ns_fixed, r.ns_float);
        csv += line;
    }
    std::fputs(csv.c_str(), stdout);
    if (out_path != nullptr) {
        std::FILE* f = std::fopen(out_path, "w");
        if (f == nullptr) {
            std::fprintf(stderr, "fixed_accuracy: cannot write %s\n", out_path);
            return 1;
        }
        std::fputs(csv.c_str(), f);
        std::fclose(f);
    }
    return 0;
}
