#pragma once
/// The one conversion from a JavaScript number to lockbox's fixed-point formats. A JavaScript
/// number is an IEEE-754 binary64 value; the bindings receive its 64-bit pattern (read from a
/// DataView, never computed with) and decode it here with integer arithmetic only: sign,
/// exponent and 53-bit significand, shifted to the target's fraction bits and rounded once,
/// to nearest with ties away from zero (docs/numerics.md). Every engine and machine therefore
/// gets the same raw value, and a number with a finite decimal expansion converts exactly as
/// `Fixed::Parse` converts that expansion.

#include <cstdint>

namespace lockbox::web {

/// Why a number was refused.
enum class NumberError : int32_t {
    none = 0,        ///< converted
    notFinite = 1,   ///< NaN or an infinity
    outOfRange = 2,  ///< the rounded magnitude exceeds the format's largest raw value
};

/// A converted raw value, or the reason it was refused (raw is then 0).
struct RawNumber {
    int64_t raw = 0;
    NumberError error = NumberError::none;
};

/// The binary64 value with bit pattern `bits` as a raw fixed-point value with `fracBits`
/// fraction bits (0..62), rounded to nearest (ties away from zero); refused when not finite
/// or when the rounded magnitude exceeds `maxRaw` (> 0). -0 and values below half a unit
/// give 0.
RawNumber DoubleBitsToRaw(uint64_t bits, int fracBits, int64_t maxRaw) noexcept;

/// DoubleBitsToRaw for `Fixed` (Q16.16: 16 fraction bits, |raw| <= 2^31 - 1).
RawNumber DoubleBitsToFixedRaw(uint64_t bits) noexcept;

/// DoubleBitsToRaw for `Wide` (Q32.32: 32 fraction bits, |raw| <= 2^63 - 1).
RawNumber DoubleBitsToWideRaw(uint64_t bits) noexcept;

/// A short English description of `error` ("ok" for none). Never null; static storage.
const char* NumberErrorMessage(NumberError error) noexcept;

}  // namespace lockbox::web
