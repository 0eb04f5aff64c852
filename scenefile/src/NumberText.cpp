// Scene-file numbers: decimal and hexadecimal-float text to Fixed and Wide, and back to the
// shortest decimal. Integer arithmetic only (docs/scene-files.md, "Numbers").
#include "lockbox/scenefile/NumberText.h"

#include <cstdint>

#include "lockbox/fixed/detail/Decimal.h"

namespace lockbox::scenefile {

namespace {

// lockbox::detail by its full name: inside lockbox::scenefile, `detail` alone could mean
// lockbox::scenefile::detail when this file is compiled together with the loader's (the cross
// build's jumbo translation units do).
namespace fixed_detail = ::lockbox::detail;

constexpr uint64_t kPow10[20] = {1ull,
                                 10ull,
                                 100ull,
                                 1000ull,
                                 10000ull,
                                 100000ull,
                                 1000000ull,
                                 10000000ull,
                                 100000000ull,
                                 1000000000ull,
                                 10000000000ull,
                                 100000000000ull,
                                 1000000000000ull,
                                 10000000000000ull,
                                 100000000000000ull,
                                 1000000000000000ull,
                                 10000000000000000ull,
                                 100000000000000000ull,
                                 1000000000000000000ull,
                                 10000000000000000000ull};

NumberError FromDecimalError(fixed_detail::DecimalError e) noexcept {
    switch (e) {
        case fixed_detail::DecimalError::None: return NumberError::e_ok;
        case fixed_detail::DecimalError::OutOfRange: return NumberError::e_outOfRange;
        default: return NumberError::e_malformed;
    }
}

// The common short case of JSON number text (at most 18 significant digits, a small exponent):
// N * 10^p rounded to fracBits fraction bits with one 64-bit division, which is the same
// correctly rounded value (ties away from zero) that detail::ParseDecimal computes digit by
// digit. Returns false when the text is not of that form; ParseDecimal then decides.
bool ParseShort(std::string_view text, int fracBits, int64_t maxRaw, int64_t& raw, NumberError& error) noexcept {
    size_t i = 0;
    const size_t n = text.size();
    const bool negative = i < n && text[i] == '-';
    if (negative) ++i;
    uint64_t mantissa = 0;
    int significant = 0;
    int fractionDigits = 0;
    bool digits = false;
    bool point = false;
    for (; i < n; ++i) {
        const char c = text[i];
        if (c == '.') {
            if (point) return false;
            point = true;
            continue;
        }
        if (c < '0' || c > '9') break;
        digits = true;
        if (point) ++fractionDigits;
        if (mantissa == 0 && c == '0') continue;
        if (++significant > 18) return false;
        mantissa = mantissa * 10 + static_cast<uint64_t>(c - '0');
    }
    if (!digits) return false;
    int exponent = 0;
    if (i < n && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        bool expNegative = false;
        if (i < n && (text[i] == '+' || text[i] == '-')) expNegative = text[i++] == '-';
        int expDigits = 0;
        for (; i < n && text[i] >= '0' && text[i] <= '9'; ++i) {
            if (++expDigits > 4) return false;
            exponent = exponent * 10 + (text[i] - '0');
        }
        if (expDigits == 0) return false;
        if (expNegative) exponent = -exponent;
    }
    if (i != n) return false;
    if (mantissa == 0) {
        raw = 0;
        error = NumberError::e_ok;
        return true;
    }
    const int power = exponent - fractionDigits;
    const uint64_t limit = static_cast<uint64_t>(maxRaw);
    uint64_t magnitude = 0;
    if (power >= 0) {
        if (power > 19) return false;
        const uint64_t whole = limit >> fracBits;  // the largest integer value that fits
        if (mantissa > whole || kPow10[power] > whole / mantissa) {
            error = NumberError::e_outOfRange;
            return true;
        }
        magnitude = (mantissa * kPow10[power]) << fracBits;
        if (magnitude > limit) {
            error = NumberError::e_outOfRange;
            return true;
        }
    } else {
        const int q = -power;
        if (q > 19) return false;
        const uint64_t den = kPow10[q];
        uint64_t rem = 0;
        if (mantissa < (uint64_t{1} << (63 - fracBits))) {
            const uint64_t num = mantissa << fracBits;
            magnitude = num / den;
            rem = num - magnitude * den;
        } else {
            // mantissa < 10^18 < 2^60, so mantissa * 2^fracBits < 2^92: a 128-bit numerator
            // whose quotient must still fit 64 bits to be in range.
            const fixed_detail::DivModU128Result qr = fixed_detail::DivModU128(
                fixed_detail::MulU64(mantissa, uint64_t{1} << fracBits), fixed_detail::U128{0, den});
            if (qr.quot.hi != 0) {
                error = NumberError::e_outOfRange;
                return true;
            }
            magnitude = qr.quot.lo;
            rem = qr.rem.lo;
        }
        if (rem >= den - rem) ++magnitude;  // 2 rem >= den: ties away from zero
        if (magnitude > limit) {
            error = NumberError::e_outOfRange;
            return true;
        }
    }
    raw = negative ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
    error = NumberError::e_ok;
    return true;
}

NumberError ParseRaw(std::string_view text, int fracBits, int64_t maxRaw, int64_t& raw) noexcept {
    NumberError error = NumberError::e_ok;
    if (ParseShort(text, fracBits, maxRaw, raw, error)) return error;
    const fixed_detail::DecimalResult r = fixed_detail::ParseDecimal(text, fracBits, maxRaw);
    if (r.error != fixed_detail::DecimalError::None) return FromDecimalError(r.error);
    raw = r.raw;
    return NumberError::e_ok;
}

int HexDigit(char c) noexcept {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// binary32 bits to the nearest value with fracBits fraction bits, ties away from zero.
NumberError HexToRaw(std::string_view hex, int fracBits, int64_t maxRaw, int64_t& raw) noexcept {
    if (hex.size() != 8) return NumberError::e_malformed;
    uint32_t bits = 0;
    for (char c : hex) {
        const int d = HexDigit(c);
        if (d < 0) return NumberError::e_malformed;
        bits = (bits << 4) | static_cast<uint32_t>(d);
    }
    const bool negative = (bits >> 31) != 0;
    const int biased = static_cast<int>((bits >> 23) & 0xFFu);
    const uint64_t fraction = bits & 0x7FFFFFu;
    if (biased == 0xFF) return NumberError::e_notFinite;
    // value = m * 2^e with m < 2^24: subnormals have no implicit bit and e = -149.
    const uint64_t m = biased == 0 ? fraction : (fraction | 0x800000u);
    const int e = biased == 0 ? -149 : biased - 150;
    const int shift = e + fracBits;  // raw = m * 2^shift
    uint64_t magnitude = 0;
    if (m != 0) {
        if (shift >= 0) {
            // m < 2^24, so m << shift fits 64 bits up to shift 39; beyond, it is out of range.
            if (shift > 39) return NumberError::e_outOfRange;
            magnitude = m << shift;
        } else if (-shift < 25) {
            const int k = -shift;
            magnitude = (m + (uint64_t{1} << (k - 1))) >> k;
        }  // else m / 2^k < 1/2: rounds to zero
    }
    if (magnitude > static_cast<uint64_t>(maxRaw)) return NumberError::e_outOfRange;
    raw = negative ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
    return NumberError::e_ok;
}

// Adds one unit in the last place of a string of decimal digits (with a '.' somewhere).
std::string Increment(std::string s) {
    for (size_t i = s.size(); i-- > 0;) {
        if (s[i] == '.') continue;
        if (s[i] != '9') {
            ++s[i];
            return s;
        }
        s[i] = '0';
    }
    return "1" + s;
}

// Drops trailing fraction zeros and a bare point.
std::string Trim(std::string s) {
    if (s.find('.') == std::string::npos) return s;
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

// The shortest decimal whose value rounds to raw. With x the exact value, M its magnitude in
// units of 2^-f, and the first k fraction digits of x written out (lo, the truncation), the
// remainder r = (x's fraction * 10^k) mod 2^f gives both neighbours' rounding exactly:
//   lo * 2^f        = M - r / 10^k        -> rounds to M iff 2r <= 10^k (a tie rounds away
//                                             from zero, i.e. up to M)
//   (lo + 10^-k) 2^f = M + (2^f - r) / 10^k -> rounds to M iff 2 (2^f - r) < 10^k
// The first k where one of them reads back wins (the nearer if both), so the text is the
// shortest; at most 5 fraction digits for Q16.16 and 10 for Q32.32.
std::string FormatRaw(int64_t raw, int fracBits, int64_t maxRaw) {
    const bool negative = raw < 0;
    const uint64_t magnitude = negative ? uint64_t{0} - static_cast<uint64_t>(raw) : static_cast<uint64_t>(raw);
    const uint64_t one = uint64_t{1} << fracBits;
    const std::string sign = negative ? "-" : "";
    std::string text = std::to_string(magnitude >> fracBits);
    uint64_t rem = magnitude & (one - 1);
    if (rem == 0) return raw == 0 ? "0" : sign + text;
    // A magnitude beyond the format (only a hand-made raw can have one) reads back as nothing;
    // its exact decimal is written.
    const bool readable = magnitude <= static_cast<uint64_t>(maxRaw);
    text += '.';
    for (int k = 1; k <= fracBits; ++k) {
        rem *= 10;
        text += static_cast<char>('0' + (rem >> fracBits));
        rem &= one - 1;
        if (rem == 0) return sign + Trim(text);
        if (!readable || k > 19) continue;
        const uint64_t scale = kPow10[k];
        const bool lo = 2 * rem <= scale;
        const bool hi = 2 * (one - rem) < scale;
        if (lo && (!hi || rem <= one - rem)) return sign + Trim(text);
        if (hi) return sign + Trim(Increment(text));
    }
    return sign + Trim(text);
}

}  // namespace

NumberError ParseFixed(std::string_view text, Fixed& out) noexcept {
    int64_t raw = 0;
    const NumberError e = ParseRaw(text, Fixed::kFractionBits, Fixed::kMaxRaw, raw);
    if (e == NumberError::e_ok) out = Fixed::FromRaw(static_cast<int32_t>(raw));
    return e;
}

NumberError ParseWide(std::string_view text, Wide& out) noexcept {
    int64_t raw = 0;
    const NumberError e = ParseRaw(text, Wide::kFractionBits, Wide::kMaxRaw, raw);
    if (e == NumberError::e_ok) out = Wide::FromRaw(raw);
    return e;
}

NumberError HexFloatToFixed(std::string_view hex, Fixed& out) noexcept {
    int64_t raw = 0;
    const NumberError e = HexToRaw(hex, Fixed::kFractionBits, Fixed::kMaxRaw, raw);
    if (e == NumberError::e_ok) out = Fixed::FromRaw(static_cast<int32_t>(raw));
    return e;
}

NumberError HexFloatToWide(std::string_view hex, Wide& out) noexcept {
    int64_t raw = 0;
    const NumberError e = HexToRaw(hex, Wide::kFractionBits, Wide::kMaxRaw, raw);
    if (e == NumberError::e_ok) out = Wide::FromRaw(raw);
    return e;
}

std::string FormatFixed(Fixed value) { return FormatRaw(value.Raw(), Fixed::kFractionBits, Fixed::kMaxRaw); }

std::string FormatWide(Wide value) { return FormatRaw(value.Raw(), Wide::kFractionBits, Wide::kMaxRaw); }

}  // namespace lockbox::scenefile
