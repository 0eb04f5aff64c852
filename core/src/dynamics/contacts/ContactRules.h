#pragma once
// Which shape pairs make contacts, and in which order a pair's collider takes them. The contact
// manager applies these to new pairs; the snapshot checks hold a restored contact to them.

#include "lockbox/collision/Shape.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox::core_detail {

/// True when a collider exists for this pair of shape types (in either order): every pair but
/// two surfaces (edges and chains are one-sided, and have no edge/edge collider).
bool ShapesCanCollide(b2Shape::Type typeA, b2Shape::Type typeB) noexcept;
/// True when the pair must be swapped so that A has the "primary" type of the collider
/// (polygon before circle, edge/chain before circle or polygon).
bool ShapesNeedSwap(b2Shape::Type typeA, b2Shape::Type typeB) noexcept;

}  // namespace lockbox::core_detail
