// Linked into every fuzz target. Hostile input may carry values that leave the fixed-point
// formats' range. Default builds then saturate and count, which is the documented answer to
// such input; checked builds would trap and abort. A fuzz run looks for crashes, hangs and
// sanitizer reports, not for saturations, so it takes the saturated result in every build
// (the sanitize preset is a checked build).

#include <cstdint>

#include "lockbox/fixed/Overflow.h"

namespace {

void AcceptSaturatedResult(const char* /*op*/, int64_t /*a*/, int64_t /*b*/) {}

[[maybe_unused]] const bool g_installed = (lockbox::SetOverflowTrapHandler(&AcceptSaturatedResult), true);

}  // namespace
