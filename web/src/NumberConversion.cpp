#include "NumberConversion.h"

#include <limits>

namespace lockbox::web {

RawNumber DoubleBitsToRaw(uint64_t bits, int fracBits, int64_t maxRaw) noexcept {
    const bool negative = (bits >> 63) != 0;
    const int biased = static_cast<int>((bits >> 52) & 0x7FF);
    const uint64_t fraction = bits & ((uint64_t{1} << 52) - 1);
    if (biased == 0x7FF) return {0, NumberError::notFinite};
    // value = significand * 2^exponent exactly, with a 53-bit integer significand (subnormals
    // have no hidden bit and the smallest exponent).
    const uint64_t significand = biased == 0 ? fraction : fraction | (uint64_t{1} << 52);
    const int exponent = (biased == 0 ? 1 : biased) - 1075;
    if (significand == 0) return {};
    // raw = significand * 2^shift, rounded.
    const int shift = exponent + fracBits;
    uint64_t magnitude;
    if (shift >= 0) {
        // The significand's top bit is at most bit 52: from a shift of 11 on, the product
        // reaches 2^63 and exceeds every maxRaw.
        if (shift >= 11) return {0, NumberError::outOfRange};
        magnitude = significand << shift;
    } else if (shift <= -54) {
        // significand < 2^53 <= 2^(-shift - 1): below half a unit.
        return {};
    } else {
        const int drop = -shift;
        const uint64_t kept = significand >> drop;
        const uint64_t rest = significand & ((uint64_t{1} << drop) - 1);
        const uint64_t half = uint64_t{1} << (drop - 1);
        magnitude = kept + (rest >= half ? 1 : 0);  // ties go up in magnitude: away from zero
    }
    if (magnitude > static_cast<uint64_t>(maxRaw)) return {0, NumberError::outOfRange};
    const auto value = static_cast<int64_t>(magnitude);
    return {negative ? -value : value, NumberError::none};
}

RawNumber DoubleBitsToFixedRaw(uint64_t bits) noexcept {
    return DoubleBitsToRaw(bits, 16, std::numeric_limits<int32_t>::max());
}

RawNumber DoubleBitsToWideRaw(uint64_t bits) noexcept {
    return DoubleBitsToRaw(bits, 32, std::numeric_limits<int64_t>::max());
}

const char* NumberErrorMessage(NumberError error) noexcept {
    switch (error) {
        case NumberError::none: return "ok";
        case NumberError::notFinite: return "not a finite number";
        case NumberError::outOfRange: return "out of range";
    }
    return "unknown";
}

}  // namespace lockbox::web
