#pragma once
/// @file
/// The numbers of a scene file, in and out, with integer arithmetic only.
///
/// In: decimal text ("-12.375", "1e-3") is rounded to the nearest Q16.16 (or Q32.32) value,
/// ties away from zero: Fixed::Parse's rule (docs/numerics.md). R.U.B.E.'s hexadecimal floats
/// (8 hex digits, the bits of an IEEE-754 binary32, e.g. "3F800000" = 1) are decoded from those
/// bits and rounded by the same rule; no float is ever formed. So a file's numbers, and the
/// world built from them, are the same on every machine.
///
/// Out: the shortest decimal that reads back to the same value (at most 5 fraction digits for
/// Q16.16, 10 for Q32.32), so writing, reading and writing again gives the same text.

#include <string>
#include <string_view>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Wide.h"

namespace lockbox::scenefile {

/// Why a number's text was refused.
enum class NumberError : uint8 {
    e_ok = 0,
    e_malformed,   ///< not decimal text, or not 8 hexadecimal digits
    e_notFinite,   ///< a hexadecimal float that is infinite or NaN
    e_outOfRange,  ///< beyond the format's range (Q16.16: +-32767.99998)
};

/// Decimal text (JSON number syntax, or Fixed::Parse's wider syntax) to the nearest Fixed.
LOCKBOX_API NumberError ParseFixed(std::string_view text, Fixed& out) noexcept;
/// Decimal text to the nearest Wide (Q32.32).
LOCKBOX_API NumberError ParseWide(std::string_view text, Wide& out) noexcept;
/// Eight hexadecimal digits (either case) holding binary32 bits, to the nearest Fixed.
LOCKBOX_API NumberError HexFloatToFixed(std::string_view hex, Fixed& out) noexcept;
/// Eight hexadecimal digits holding binary32 bits, to the nearest Wide.
LOCKBOX_API NumberError HexFloatToWide(std::string_view hex, Wide& out) noexcept;

/// The shortest decimal text that ParseFixed reads back as `value` ("0", "-1.5", "0.1").
LOCKBOX_API std::string FormatFixed(Fixed value);
/// The shortest decimal text that ParseWide reads back as `value`.
LOCKBOX_API std::string FormatWide(Wide value);

}  // namespace lockbox::scenefile
