#include "dynamics/lanes/IntegerLanes.h"

#include <atomic>

namespace lockbox::lanes {

namespace {
// Tests switch the lanes off to compare the two paths; the choice never changes a result.
std::atomic<bool> g_allowed{true};
}  // namespace

bool Allowed() noexcept { return g_allowed.load(std::memory_order_relaxed); }
void Allow(bool allow) noexcept { g_allowed.store(allow, std::memory_order_relaxed); }

}  // namespace lockbox::lanes
