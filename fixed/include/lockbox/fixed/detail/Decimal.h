#pragma once
/// Exact decimal -> binary fixed-point conversion with integers only, shared by the `_fx`
/// literal (compile time) and Fixed::Parse (run time). No floating point is involved, so the
/// result is the same everywhere: the nearest value with `fracBits` fraction bits, ties away
/// from zero.

#include <cstdint>
#include <string_view>

namespace lockbox::detail {

enum class DecimalError : uint8_t {
    None,
    Empty,         ///< no digits
    BadCharacter,  ///< something other than [+-]digits[.digits][e[+-]digits]
    TooLong,       ///< more than kMaxDecimalDigits significant digits
    OutOfRange,    ///< magnitude beyond the target format
};

inline constexpr int kMaxDecimalDigits = 64;

struct DecimalResult {
    int64_t raw = 0;
    DecimalError error = DecimalError::None;
};

/// Parses text into a raw fixed-point value with `fracBits` fraction bits whose magnitude
/// must not exceed `maxRaw`.
constexpr DecimalResult ParseDecimal(std::string_view text, int fracBits, int64_t maxRaw) noexcept {
    DecimalResult out;
    size_t i = 0;
    bool negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';

    // Mantissa digits without leading zeros: value = 0.d1 d2 ... dn * 10^pointPos.
    uint8_t digits[kMaxDecimalDigits] = {};
    int count = 0;
    int pointPos = 0;
    bool seenPoint = false;
    bool anyDigit = false;
    for (; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '\'') continue;  // C++ digit separator in literals
        if (ch == '.') {
            if (seenPoint) return {0, DecimalError::BadCharacter};
            seenPoint = true;
            continue;
        }
        if (ch < '0' || ch > '9') break;
        anyDigit = true;
        if (count == 0 && ch == '0') {
            if (seenPoint) --pointPos;  // 0.00d: the point sits further left of d
            continue;
        }
        if (count == kMaxDecimalDigits) {
            if (!seenPoint) return {0, DecimalError::TooLong};
            // Dropping digits past the 64th cannot move the rounding: it only matters on an
            // exact tie, and a tie has at most 17 fraction digits.
            continue;
        }
        digits[count++] = static_cast<uint8_t>(ch - '0');
        if (!seenPoint) ++pointPos;
    }
    if (!anyDigit) return {0, DecimalError::Empty};

    int exponent = 0;
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        bool expNeg = false;
        if (i < text.size() && (text[i] == '+' || text[i] == '-')) expNeg = text[i++] == '-';
        bool expDigit = false;
        for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
            expDigit = true;
            if (exponent < 1000) exponent = exponent * 10 + (text[i] - '0');
        }
        if (!expDigit) return {0, DecimalError::BadCharacter};
        if (expNeg) exponent = -exponent;
    }
    // Literal suffixes (f, F, l, L) are tolerated so that "1.5f"-style text parses.
    while (i < text.size() && (text[i] == 'f' || text[i] == 'F' || text[i] == 'l' || text[i] == 'L')) ++i;
    if (i != text.size()) return {0, DecimalError::BadCharacter};
    if (count == 0) return {0, DecimalError::None};  // zero

    // Value = 0.d1d2...dn * 10^(pointPos + exponent).
    const int point = pointPos + exponent;
    if (point > 19) return {0, DecimalError::OutOfRange};
    // Integer part: digits before the point.
    uint64_t integer = 0;
    for (int k = 0; k < point; ++k) integer = integer * 10 + (k < count ? digits[k] : 0);
    // Fraction: digits after the point, possibly preceded by -point zeros.
    uint8_t frac[kMaxDecimalDigits + 1] = {};
    int fracCount = 0;
    const int lead = point < 0 ? -point : 0;
    if (lead > kMaxDecimalDigits) {
        // Far below one ULP: rounds to zero.
        return {0, DecimalError::None};
    }
    for (int k = 0; k < lead; ++k) frac[fracCount++] = 0;
    for (int k = point < 0 ? 0 : point; k < count && fracCount <= kMaxDecimalDigits; ++k) frac[fracCount++] = digits[k];
    // floor(fraction * 2^(fracBits+1)) by repeated doubling of the decimal digit string; the
    // extra bit decides the rounding (ties go up on the magnitude, i.e. away from zero).
    uint64_t bits = 0;
    for (int b = 0; b <= fracBits; ++b) {
        int carry = 0;
        for (int k = fracCount - 1; k >= 0; --k) {
            const int v = frac[k] * 2 + carry;
            frac[k] = static_cast<uint8_t>(v % 10);
            carry = v / 10;
        }
        bits = (bits << 1) | static_cast<uint64_t>(carry);
    }
    const uint64_t fracRaw = (bits + 1) >> 1;
    if (integer > static_cast<uint64_t>(maxRaw >> fracBits) + 1) return {0, DecimalError::OutOfRange};
    const uint64_t magnitude = (integer << fracBits) + fracRaw;
    if (magnitude > static_cast<uint64_t>(maxRaw)) return {0, DecimalError::OutOfRange};
    out.raw = negative ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
    return out;
}

constexpr const char* DecimalErrorMessage(DecimalError e) noexcept {
    switch (e) {
        case DecimalError::None: return "ok";
        case DecimalError::Empty: return "no digits";
        case DecimalError::BadCharacter: return "not a decimal number";
        case DecimalError::TooLong: return "too many significant digits";
        case DecimalError::OutOfRange: return "out of range";
    }
    return "unknown";
}

}  // namespace lockbox::detail
