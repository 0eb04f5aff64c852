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
// The innermost capture on this thread; nullptr: saturations go to t_saturations.
thread_local uint64_t* t_sink = nullptr;

uint64_t& Sink() noexcept { return t_sink != nullptr ? *t_sink : t_saturations; }

}  // namespace

OverflowTrapHandler SetOverflowTrapHandler(OverflowTrapHandler handler) noexcept { return g_handler.exchange(handler); }

uint64_t SaturationCount() noexcept { return t_saturations; }

void ResetSaturationCount() noexcept { t_saturations = 0; }

void AddSaturations(uint64_t count) noexcept { Sink() += count; }

SaturationCapture::SaturationCapture(uint64_t* sink) noexcept : m_previous(t_sink) { t_sink = sink; }

SaturationCapture::~SaturationCapture() { t_sink = m_previous; }

namespace detail {

void OnOverflow(const char* op, int64_t a, int64_t b) noexcept {
    ++Sink();
    if constexpr (kOverflowTraps) {
        OverflowTrapHandler h = g_handler.load();
        (h ? h : DefaultTrap)(op, a, b);
    }
}

}  // namespace detail
}  // namespace lockbox
