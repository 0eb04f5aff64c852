// Integer-only trigonometry kernels on raw Q16.16 values (radians; raw = value * 2^16).
//
// Every kernel uses int32/int64/uint64 arithmetic only (no floating point, no __int128), has no
// undefined behaviour for any input, and gives the same bits on every platform. Accuracy is
// measured in Q16.16 ULP (2^-16 absolute); "CR" means correctly rounded (error <= 0.5 ULP).
#pragma once

#include <cstdint>

#include "lockbox/Export.h"

namespace lockbox::detail {

/// pi in Q16.16, correctly rounded: 205887 = 3.14159... (pi * 2^16 = 205887.416, so raw 205887
/// is 0.42 ULP below pi).
inline constexpr int32_t kPiRaw = 205887;
/// 2*pi in Q16.16, correctly rounded: 411775 (2 pi * 2^16 = 411774.832; note kTwoPiRaw is NOT
/// 2 * kPiRaw).
inline constexpr int32_t kTwoPiRaw = 411775;
/// pi/2 in Q16.16, correctly rounded: 102944 (102943.708).
inline constexpr int32_t kHalfPiRaw = 102944;
/// pi/4 in Q16.16, correctly rounded: 51472 (51471.854).
inline constexpr int32_t kQuarterPiRaw = 51472;

/// pi in "raw Q16.16 units with 32 more fraction bits", i.e. round(pi * 2^48) (error < 2^-49 rad).
/// For exact turn arithmetic: angle = (wrapped_raw << 32) + turns * kTwoPiQ48 stays within
/// int64 for |turns| <= 5215 (and more when wrapped_raw is small).
inline constexpr int64_t kPiQ48 = 884279719003555;
/// 2*pi as round(2 pi * 2^48) = 2 * kPiQ48 (error < 2^-48 rad).
inline constexpr int64_t kTwoPiQ48 = 1768559438007110;

/// Sine and cosine of a Q16.16 angle in radians, computed together.
/// angle: any int32 raw value (|angle| <= 32768 rad); the argument is reduced exactly (pi/2 is
/// carried to ~2^-79), so large angles lose nothing. Outputs are raw Q16.16 in [-65536, 65536].
/// Accuracy: <= 1 ULP guaranteed over the whole int32 range, and correctly rounded (<= 0.5 ULP)
/// for all but a handful of inputs (internal error < 2^-31 rad before the final rounding).
/// Exact: sin(0) = 0, cos(0) = 65536, sin(-x) = -sin(x), cos(-x) = cos(x) for every x
/// (INT32_MIN included).
LOCKBOX_API void SinCosRaw(int32_t angle, int32_t* s, int32_t* c) noexcept;

/// Four-quadrant arc tangent of y/x in Q16.16 radians; y and x are raw values of any common
/// scale (only their ratio matters), any int32 values including INT32_MIN.
/// Result in [-kPiRaw, kPiRaw] (= [-pi, pi] rounded). atan2(0, 0) = 0; atan2(0, x < 0) = +pi
/// (205887) as in C for +0; atan2(0, x > 0) = 0; atan2(y != 0, 0) = +-pi/2; diagonals give
/// +-pi/4, +-3pi/4, all correctly rounded. Exact symmetry atan2(-y, x) = -atan2(y, x) for y != 0.
/// Accuracy: <= 1 ULP for every input pair; correctly rounded except for rare near-ties
/// (internal error ~2^-32 rad).
LOCKBOX_API int32_t Atan2Raw(int32_t y, int32_t x) noexcept;

/// Wraps a Q16.16 angle (radians) into the half-open real interval [-pi, pi).
/// Semantics: returns round(a - n * 2pi) (to nearest, raw units) where the integer n is chosen
/// so that the EXACT value a - n * 2pi (a as a real number) lies in [-pi, pi). Whole turns of the
/// exact 2pi are removed (2pi carried to 2^-48 rad; proven exact for every int32 input, so the
/// only error is the single final rounding, <= 0.5 ULP). Because pi is irrational, no raw value
/// equals +-pi, and the raw values inside [-pi, pi) are exactly [-205887, 205887]: both
/// +-kPiRaw are included (kPiRaw = 205887 is 0.42 ULP below pi, so WrapAngleRaw(kPiRaw) ==
/// kPiRaw, while WrapAngleRaw(kPiRaw + 1) == -kPiRaw). Idempotent: inputs already in
/// [-205887, 205887] are returned unchanged.
LOCKBOX_API int32_t WrapAngleRaw(int32_t a) noexcept;

/// Same as WrapAngleRaw, and stores in *turns the number n of whole turns removed, so that
/// a = result + n * 2pi up to the final rounding (|a/2^16 - (result/2^16 + n 2pi)| <= 2^-17).
/// n is in [-5215, 5215]. turns must not be null.
LOCKBOX_API int32_t WrapAngleTurnsRaw(int32_t a, int32_t* turns) noexcept;

}  // namespace lockbox::detail
