#pragma once
// A hint to the processor inside a wait loop: the waiting core yields its pipeline (and, on a
// shared core, its sibling's share) for a few dozen cycles. It changes no result.

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace lockbox {

inline void SpinPause() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("yield");
#endif
}

}  // namespace lockbox
