// Run-time double -> Fixed, for tools only. Not deterministic across platforms: x87 excess
// precision and FMA contraction can change the last bit, which is why simulation code never
// calls it (see docs/numerics.md).
#include "lockbox/fixed/Fixed.h"

namespace lockbox {

Fixed Fixed::FromDoubleNondeterministic(double v) noexcept {
    if (!(v == v)) return Fixed();
    const double scaled = v * static_cast<double>(kOneRaw);
    const double limit = static_cast<double>(kMaxRaw);
    if (scaled >= limit) return FromRaw(kMaxRaw);
    if (scaled <= -limit) return FromRaw(-kMaxRaw);
    const bool negative = scaled < 0;
    const double mag = negative ? -scaled : scaled;
    const auto whole = static_cast<int64_t>(mag);
    const int64_t r = whole + ((mag - static_cast<double>(whole)) >= 0.5 ? 1 : 0);
    return FromRaw(static_cast<int32_t>(negative ? -r : r));
}

}  // namespace lockbox
