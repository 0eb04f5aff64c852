#include "lockbox/fixed/Overflow.h"

#include <atomic>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>

namespace lockbox {
namespace {

// Used only when kOverflowTraps (checked builds); [[maybe_unused]] keeps clang quiet elsewhere.
[[maybe_unused]] void DefaultTrap(const char* op, int64_t a, int64_t b) {
    std::fprintf(stderr, "lockbox: fixed-point overflow in %s (operands raw %" PRId64 ", %" PRId64 ")\n", op, a, b);
    std::fflush(stderr);
    std::abort();
}

std::atomic<OverflowTrapHandler> g_handler{nullptr};
thread_local uint64_t t_saturations = 0;

}  // namespace

OverflowTrapHandler SetOverflowTrapHandler(OverflowTrapHandler handler) noexcept { return g_handler.exchange(handler); }

uint64_t SaturationCount() noexcept { return t_saturations; }

void ResetSaturationCount() noexcept { t_saturations = 0; }

namespace detail {

void OnOverflow(const char* op, int64_t a, int64_t b) noexcept {
    ++t_saturations;
    if constexpr (kOverflowTraps) {
        OverflowTrapHandler h = g_handler.load();
        (h ? h : DefaultTrap)(op, a, b);
    }
}

}  // namespace detail
}  // namespace lockbox
