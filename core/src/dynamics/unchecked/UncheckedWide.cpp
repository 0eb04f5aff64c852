#include "dynamics/unchecked/UncheckedWide.h"

#include <atomic>

namespace lockbox::solver {

namespace {
// A switch for tests, read once per range of rows; it never changes a result.
std::atomic<bool> g_allowed{true};
}  // namespace

bool UncheckedRowsAllowed() noexcept { return g_allowed.load(std::memory_order_relaxed); }
void AllowUncheckedRows(bool allow) noexcept { g_allowed.store(allow, std::memory_order_relaxed); }

}  // namespace lockbox::solver
