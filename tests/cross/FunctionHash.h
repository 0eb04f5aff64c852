#pragma once
// Fixed-function hashes shared by tests/fixed/function_hash_test.cpp (GoogleTest) and the
// standalone cross-build driver (tests/cross/cross_driver.cpp): FNV-1a hashes of the integer
// math kernels over fixed strided input sets, and their golden values. Inputs come from
// integer formulas and a fixed LCG only: nothing here depends on the platform.
#include <cstdint>

#include "lockbox/fixed/detail/Sqrt.h"
#include "lockbox/fixed/detail/Trig.h"

namespace lockbox::function_hash {

// 64-bit FNV-1a over the little-endian bytes of each 32-bit value (endianness-independent).
class Fnv1a {
public:
    void Add32(uint32_t v) {
        for (int i = 0; i < 4; ++i) {
            hash_ ^= (v >> (8 * i)) & 0xFFu;
            hash_ *= 0x100000001B3ull;
        }
    }
    void AddI32(int32_t v) { Add32(static_cast<uint32_t>(v)); }
    void Add64(uint64_t v) {
        Add32(static_cast<uint32_t>(v));
        Add32(static_cast<uint32_t>(v >> 32));
    }
    uint64_t Value() const { return hash_; }

private:
    uint64_t hash_ = 0xCBF29CE484222325ull;
};

// Knuth's MMIX LCG; only its top bits are used.
class Lcg {
public:
    uint64_t Next() {
        state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
        return state_;
    }

private:
    uint64_t state_ = 0x1234567887654321ull;
};

inline constexpr int64_t kInt32Min = -2147483647 - 1;
inline constexpr int64_t kInt32Max = 2147483647;

inline uint64_t HashSqrtRaw() {
    Fnv1a h;
    for (int64_t x = -1000; x <= kInt32Max; x += 4093) h.AddI32(lockbox::detail::SqrtRaw(static_cast<int32_t>(x)));
    for (int32_t x = 0; x < 65536; ++x) h.AddI32(lockbox::detail::SqrtRaw(x));
    return h.Value();
}

inline uint64_t HashIsqrt64() {
    Fnv1a h;
    Lcg rng;
    for (int i = 0; i < 200000; ++i) {
        const uint64_t r = rng.Next();
        const uint64_t n = r >> (r >> 58);  // shift 0..63 from the top bits
        h.Add64(lockbox::detail::IsqrtRound64(n));
        h.Add32(lockbox::detail::IsqrtFloor64(n));
    }
    return h.Value();
}

inline uint64_t HashSinCos() {
    Fnv1a h;
    for (int64_t x = kInt32Min; x <= kInt32Max; x += 8191) {
        int32_t s = 0, c = 0;
        lockbox::detail::SinCosRaw(static_cast<int32_t>(x), &s, &c);
        h.AddI32(s);
        h.AddI32(c);
    }
    for (int32_t x = -411775; x <= 411775; x += 5) {
        int32_t s = 0, c = 0;
        lockbox::detail::SinCosRaw(x, &s, &c);
        h.AddI32(s);
        h.AddI32(c);
    }
    return h.Value();
}

inline uint64_t HashAtan2() {
    Fnv1a h;
    Lcg rng;
    for (int i = 0; i < 300000; ++i) {
        const uint64_t a = rng.Next();
        const uint64_t b = rng.Next();
        // Magnitudes of every bit length, both signs, from the top bits.
        const int32_t y = static_cast<int32_t>(static_cast<uint32_t>(a >> 32) >> ((a >> 27) & 31));
        const int32_t x = static_cast<int32_t>(static_cast<uint32_t>(b >> 32) >> ((b >> 27) & 31));
        h.AddI32(lockbox::detail::Atan2Raw(y, x));
    }
    return h.Value();
}

inline uint64_t HashWrapAngle() {
    Fnv1a h;
    for (int64_t a = kInt32Min; a <= kInt32Max; a += 4099) {
        int32_t turns = 0;
        h.AddI32(lockbox::detail::WrapAngleTurnsRaw(static_cast<int32_t>(a), &turns));
        h.AddI32(turns);
        h.AddI32(lockbox::detail::WrapAngleRaw(static_cast<int32_t>(a)));
    }
    return h.Value();
}

// Golden values (x86-64, gcc 12.2, -O2). Change only with a deliberate change of results.
inline constexpr uint64_t kGoldenSqrtRaw = 0x5a94c746bd786a29ull;
inline constexpr uint64_t kGoldenIsqrt64 = 0x2c7208454c258089ull;
inline constexpr uint64_t kGoldenSinCos = 0xd7f9c2ce862fcbccull;
inline constexpr uint64_t kGoldenAtan2 = 0xbaed0245ec00de4cull;
inline constexpr uint64_t kGoldenWrapAngle = 0x797a7f9de96a50a3ull;

/// One kernel's hash function with its name and golden value.
struct Kernel {
    const char* name;
    uint64_t (*hash)();
    uint64_t golden;
};

/// Every kernel, in a fixed order.
inline constexpr Kernel kKernels[] = {
    {"SqrtRaw", &HashSqrtRaw, kGoldenSqrtRaw},          {"Isqrt64", &HashIsqrt64, kGoldenIsqrt64},
    {"SinCosRaw", &HashSinCos, kGoldenSinCos},          {"Atan2Raw", &HashAtan2, kGoldenAtan2},
    {"WrapAngleRaw", &HashWrapAngle, kGoldenWrapAngle},
};

}  // namespace lockbox::function_hash
