// Cross-build determinism: FNV-1a hashes of the outputs of the integer math kernels over fixed
// strided input sets, compared with golden values generated once on x86-64 (gcc 12, -O2).
// Every build (gcc/clang, -O0..-O3 -march=native -ffast-math, x86-64/i686/aarch64/s390x) must
// reproduce them bit for bit. Inputs come from integer formulas and a fixed LCG only: nothing
// here depends on the platform.
#include <cstdint>
#include <cstdio>

#include <gtest/gtest.h>

#include "../cross/FunctionHash.h"

namespace LOCKBOX_TEST_FILE {

using namespace lockbox::function_hash;

::testing::AssertionResult HashIs(const char* name, uint64_t got, uint64_t want) {
    if (got == want) return ::testing::AssertionSuccess();
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: hash 0x%016llxull, golden 0x%016llxull", name,
                  static_cast<unsigned long long>(got), static_cast<unsigned long long>(want));
    return ::testing::AssertionFailure() << buf;
}

TEST(FunctionHash, SqrtRaw) { EXPECT_TRUE(HashIs("SqrtRaw", HashSqrtRaw(), kGoldenSqrtRaw)); }
TEST(FunctionHash, Isqrt64) { EXPECT_TRUE(HashIs("Isqrt64", HashIsqrt64(), kGoldenIsqrt64)); }
TEST(FunctionHash, SinCosRaw) { EXPECT_TRUE(HashIs("SinCosRaw", HashSinCos(), kGoldenSinCos)); }
TEST(FunctionHash, Atan2Raw) { EXPECT_TRUE(HashIs("Atan2Raw", HashAtan2(), kGoldenAtan2)); }
TEST(FunctionHash, WrapAngleRaw) { EXPECT_TRUE(HashIs("WrapAngleRaw", HashWrapAngle(), kGoldenWrapAngle)); }

}  // namespace LOCKBOX_TEST_FILE
