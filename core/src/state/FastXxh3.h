#pragma once
// Internal to the state code: the XXH3-64 entry points it calls, routed to libxxhash's
// runtime-dispatched variants (AVX2/AVX-512 when the CPU has them) on x86-64. XXH3's value
// does not depend on the vector width: every variant gives the same 64 bits, so hashes and
// checksums are unchanged; the SSE2 baseline the library is otherwise compiled for ran at
// ~5 GB/s here, about a third of a 1,000-body state hash. Elsewhere, and in builds that
// inline xxHash (XXH_INLINE_ALL, the cross-architecture check), the plain functions are used.

#ifndef XXH_STATIC_LINKING_ONLY
#define XXH_STATIC_LINKING_ONLY
#endif
#include <xxhash.h>

#include <cstddef>
#include <cstdint>

#if defined(__x86_64__) && !defined(XXH_INLINE_ALL) && __has_include(<xxh_x86dispatch.h>)
#define LOCKBOX_XXH3_DISPATCH 1
#ifndef XXH_DISPATCH_DISABLE_REPLACE
#define XXH_DISPATCH_DISABLE_REPLACE  // keep the plain names plain; we pick explicitly below
#endif
#include <xxh_x86dispatch.h>
#endif

namespace lockbox::state_detail {

/// XXH3-64 of `size` bytes (seed 0).
inline uint64_t Xxh3(const void* data, size_t size) noexcept {
#ifdef LOCKBOX_XXH3_DISPATCH
    return XXH3_64bits_dispatch(data, size);
#else
    return XXH3_64bits(data, size);
#endif
}

/// XXH3-64 of `size` bytes with a seed.
inline uint64_t Xxh3Seeded(const void* data, size_t size, uint64_t seed) noexcept {
#ifdef LOCKBOX_XXH3_DISPATCH
    return XXH3_64bits_withSeed_dispatch(data, size, seed);
#else
    return XXH3_64bits_withSeed(data, size, seed);
#endif
}

/// Feeds `size` bytes to a streaming XXH3-64 state.
inline void Xxh3Update(XXH3_state_t* state, const void* data, size_t size) noexcept {
#ifdef LOCKBOX_XXH3_DISPATCH
    (void)XXH3_64bits_update_dispatch(state, data, size);
#else
    (void)XXH3_64bits_update(state, data, size);
#endif
}

}  // namespace lockbox::state_detail
