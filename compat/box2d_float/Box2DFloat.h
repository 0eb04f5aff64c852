#pragma once
// Float Box2D 2.4.1 for differential tests and side-by-side benchmarks, made safe to include next
// to lockbox. Box2D 2.4.1 defines its tuning constants as macros (b2_linearSlop, b2_pi, ...)
// with the same names as lockbox's constexpr constants, so a macro would rewrite
// `lockbox::b2_linearSlop` into `lockbox::(0.005f * b2_lengthUnitsPerMeter)`. This header
// includes Box2D, keeps the float values under other names, and removes the macros.
// Include it instead of <box2d/box2d.h>, in any order relative to lockbox's headers.
#include <box2d/b2_distance.h>
#include <box2d/b2_time_of_impact.h>
#include <box2d/box2d.h>

namespace box2d_float {
inline constexpr float linearSlop = b2_linearSlop;
inline constexpr float polygonRadius = b2_polygonRadius;
inline constexpr float maxTranslation = b2_maxTranslation;
inline constexpr float pi = b2_pi;
}  // namespace box2d_float

#undef b2_maxManifoldPoints
#undef b2_maxPolygonVertices
#undef b2_aabbExtension
#undef b2_aabbMultiplier
#undef b2_linearSlop
#undef b2_angularSlop
#undef b2_polygonRadius
#undef b2_maxSubSteps
#undef b2_maxTOIContacts
#undef b2_maxLinearCorrection
#undef b2_maxAngularCorrection
#undef b2_maxTranslation
#undef b2_maxTranslationSquared
#undef b2_maxRotation
#undef b2_maxRotationSquared
#undef b2_baumgarte
#undef b2_toiBaumgarte
#undef b2_timeToSleep
#undef b2_linearSleepTolerance
#undef b2_angularSleepTolerance
#undef b2_pi
#undef b2_epsilon
#undef b2_maxFloat
#undef b2_velocityThreshold
#undef b2_nullNode
