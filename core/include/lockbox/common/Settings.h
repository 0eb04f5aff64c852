#pragma once
/// @file
/// Global tuning constants (Box2D's b2Settings.h), re-derived for Q16.16.
///
/// Every value is a Fixed (raw in the comment). Box2D's float epsilons are below the Q16.16
/// quantum (FLT_EPSILON is 0 raw), so no `b2_epsilon` exists here: each call site that needed
/// one names its own raw threshold and says why. See docs/collision.md for the table.

#include <cstdint>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/Wide.h"

namespace lockbox {

/// The manual's fixed-width integer names (Box2D's b2Settings.h), as aliases of the standard
/// fixed-width types.
///@{
using int8 = int8_t;
using int16 = int16_t;
using int32 = int32_t;
using uint8 = uint8_t;
using uint16 = uint16_t;
using uint32 = uint32_t;
using uint64 = uint64_t;
///@}

// b2_pi (raw 205887) is defined with the other scalar math in lockbox/fixed/Functions.h.

// ---- Collision --------------------------------------------------------------------------

/// Maximum contact points between two convex shapes. Do not change.
inline constexpr int32 b2_maxManifoldPoints = 2;
/// Maximum vertices of a convex polygon. Do not change (the manifold code assumes it).
inline constexpr int32 b2_maxPolygonVertices = 8;
/// Fattening of the broad-phase AABBs so that proxies need not move every step (m, raw 6554).
inline constexpr Fixed b2_aabbExtension = Fixed::FromRaw(6554);
/// Multiplier of the displacement used to predict fat AABB movement (dimensionless).
inline constexpr Fixed b2_aabbMultiplier = 2;
/// Collision and constraint tolerance (m, raw 328, +9.8e-4 relative). Chosen as in Box2D to be
/// numerically significant but visually insignificant.
inline constexpr Fixed b2_linearSlop = Fixed::FromRaw(328);
/// Collision and constraint angular tolerance: 2 degrees (rad, raw 2288).
inline constexpr Fixed b2_angularSlop = Fixed::FromRaw(2288);
/// Skin radius of polygons and edges: 2 * linearSlop (m, raw 656). Box2D writes 0.01.
inline constexpr Fixed b2_polygonRadius = Fixed::FromRaw(2 * 328);
/// Maximum sub-steps per contact in continuous physics.
inline constexpr int32 b2_maxSubSteps = 8;

// ---- Dynamics ---------------------------------------------------------------------------

/// Maximum contacts handled in one time-of-impact event.
inline constexpr int32 b2_maxTOIContacts = 32;
/// Relative normal velocity below which collisions are inelastic (m/s).
inline constexpr Fixed b2_velocityThreshold = 1;
/// Maximum linear position correction per position iteration (m, raw 13107).
inline constexpr Fixed b2_maxLinearCorrection = Fixed::FromRaw(13107);
/// Maximum angular position correction: 8 degrees (rad, raw 9151).
inline constexpr Fixed b2_maxAngularCorrection = Fixed::FromRaw(9151);
/// Maximum translation of a body per step (m). Caps speed at 120 m/s at 60 Hz.
inline constexpr Fixed b2_maxTranslation = 2;
/// b2_maxTranslation squared (m^2), compared with a step's squared translation without a square
/// root.
inline constexpr Fixed b2_maxTranslationSquared = 4;
/// Maximum rotation of a body per step: pi/2 (rad, raw 102944).
inline constexpr Fixed b2_maxRotation = Fixed::FromRaw(102944);
/// maxRotation^2 (rad^2, raw 161704).
inline constexpr Fixed b2_maxRotationSquared = Fixed::FromRaw(161704);
/// Fraction of the overlap resolved per step (dimensionless, raw 13107).
inline constexpr Fixed b2_baumgarte = Fixed::FromRaw(13107);
/// Baumgarte factor of the time-of-impact position solve (raw 49152).
inline constexpr Fixed b2_toiBaugarte = Fixed::FromRaw(49152);

// ---- Sleep ------------------------------------------------------------------------------

/// Time a body must be still before it sleeps (s). The world counts whole steps: see
/// docs/dynamics.md for how this converts to a step count.
inline constexpr Fixed b2_timeToSleep = Fixed::FromRaw(32768);
/// A body cannot sleep while its linear speed exceeds this (m/s, raw 655).
inline constexpr Fixed b2_linearSleepTolerance = Fixed::FromRaw(655);
/// A body cannot sleep while its angular speed exceeds this: 2 degrees/s (rad/s, raw 2288).
inline constexpr Fixed b2_angularSleepTolerance = Fixed::FromRaw(2288);

/// Selects the restore constructors of joints and contacts: empty objects that a snapshot or a
/// rollback frame then fills (only the engine constructs them).
struct b2RestoreTag {};

namespace core_detail {
/// The engine's own code (core/src): the one friend of the core's public classes, which keep
/// their data private. Not part of the API.
struct Engine;
}  // namespace core_detail

}  // namespace lockbox
