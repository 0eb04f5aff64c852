#pragma once
/// @file
/// Headroom telemetry (docs/stability.md): how close a world's state comes to the
/// limits of its number formats.
///
/// For each quantity class the walk records the largest raw magnitude seen and the largest raw
/// value the class's format can hold (Fixed::kMaxRaw for Q16.16 state, Wide::kMaxRaw for
/// Q32.32 mass properties and impulses), so the ratio is the fraction of the range in use.
/// Everything is integer; Fraction() converts to double for display only.
///
/// b2MeasureHeadroom walks the world outside Step. b2World::SetHeadroomTelemetry(true) makes
/// Step fill b2Profile::headroom at its end, with the step's saturation count; off by default,
/// so a Step costs nothing extra.

#include <cstdint>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

class b2World;

/// The quantity classes of the headroom walk, in table order.
enum class b2HeadroomClass : int32 {
    e_position = 0,         ///< body origins and centres of mass, m (Q16.16)
    e_angle = 1,            ///< body angles, rad (Q16.16; wrapped by the solver)
    e_velocity = 2,         ///< linear velocity components, m/s (Q16.16)
    e_angularVelocity = 3,  ///< angular velocities, rad/s (Q16.16)
    e_impulse = 4,          ///< contact and joint accumulated impulses, N*s or N*m*s (Q32.32)
    e_mass = 5,             ///< body masses, kg (Q32.32)
    e_inertia = 6,          ///< rotational inertia about the centre of mass, kg*m^2 (Q32.32)
    e_invMass = 7,          ///< inverse masses, 1/kg (Q32.32)
    e_invInertia = 8,       ///< inverse inertia, 1/(kg*m^2) (Q32.32)
    e_treeBounds = 9,       ///< broad-phase fat AABB coordinates, m (Q16.16)
    e_treeCost = 10,        ///< insertion cost 2*perimeter of the tree root, m (Q32.32)
    e_count = 11
};

/// Short name of a class ("position", "velocity", ...); "none" for e_count.
LOCKBOX_API const char* b2HeadroomClassName(b2HeadroomClass c) noexcept;

/// One class: the largest raw magnitude seen and the format's largest raw value.
struct LOCKBOX_API b2HeadroomEntry {
    uint64 maxRaw = 0;  ///< largest |raw| observed (0 when nothing of this class exists)
    uint64 limit = 0;   ///< largest |raw| of the format (Fixed::kMaxRaw or Wide::kMaxRaw)

    /// maxRaw / limit in parts per million, rounded to nearest (ties away from zero); exact
    /// integer arithmetic (128-bit product), so deterministic. 0 when limit is 0.
    int64_t PartsPerMillion() const noexcept;
    /// maxRaw / limit as a double, for display only (never fed back into a simulation).
    double Fraction() const noexcept {
        return limit == 0 ? 0.0 : static_cast<double>(maxRaw) / static_cast<double>(limit);
    }
};

/// Headroom of one world at one moment (or a running maximum, see Merge).
struct LOCKBOX_API b2Headroom {
    /// Per class, indexed by b2HeadroomClass.
    b2HeadroomEntry entries[static_cast<int32>(b2HeadroomClass::e_count)];
    /// Fixed/Wide saturations on this thread during the step (Overflow.h counter delta; 0 from
    /// b2MeasureHeadroom, and always 0 in checked builds, where an overflow traps instead).
    int64_t saturations = 0;

    /// A zeroed record with every limit set.
    b2Headroom() noexcept;

    /// The entry of one class.
    b2HeadroomEntry& operator[](b2HeadroomClass c) noexcept { return entries[static_cast<int32>(c)]; }
    /// The entry of one class (read-only).
    const b2HeadroomEntry& operator[](b2HeadroomClass c) const noexcept { return entries[static_cast<int32>(c)]; }

    /// Running maximum: keeps the larger magnitude per class and adds the saturations.
    void Merge(const b2Headroom& other) noexcept;

    /// The class with the largest fraction of its range in use (ties: the lower class index).
    b2HeadroomClass Tightest() const noexcept;
};

/// Walks the world's bodies, contacts, joints and broad-phase tree and returns the largest
/// magnitude per class. Call it outside Step (or at its end); saturations is left 0. Joint
/// impulses are read through GetReactionForce/GetReactionTorque at inv_dt = 1/256, the scale
/// the state hash uses, so impulses up to 8.3e6 N*s are measured without saturating.
LOCKBOX_API b2Headroom b2MeasureHeadroom(const b2World& world);

}  // namespace lockbox
