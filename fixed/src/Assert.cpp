// The assert handler behind LOCKBOX_ASSERT (lockbox/fixed/Assert.h).
#include "lockbox/fixed/Assert.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace lockbox {
namespace {

void DefaultAssertHandler(const char* expr, const char* msg, const char* file, int line) {
    std::fprintf(stderr, "lockbox: %s:%d: check '%s' failed: %s\n", file, line, expr, msg);
    std::fflush(stderr);
    std::abort();
}

std::atomic<b2AssertHandler> g_assertHandler{&DefaultAssertHandler};

}  // namespace

b2AssertHandler b2SetAssertHandler(b2AssertHandler handler) noexcept {
    return g_assertHandler.exchange(handler != nullptr ? handler : &DefaultAssertHandler);
}

namespace detail {

void AssertFailed(const char* expr, const char* msg, const char* file, int line) noexcept {
    g_assertHandler.load()(expr, msg, file, line);
}

}  // namespace detail
}  // namespace lockbox
