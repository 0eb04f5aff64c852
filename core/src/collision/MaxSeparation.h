#pragma once
// The separating-axis search of the polygon collision (Box2D's b2FindMaxSeparation): the edge of
// one polygon from which the other lies farthest, and that distance. The scan over every edge is
// the definition; two centred boxes, the commonest pair of all, take a closed form with its bits.

#include "lockbox/collision/PolygonShape.h"
#include "lockbox/fixed/Transform.h"

namespace lockbox::collision_detail {

/// Max separation of poly2 from the edges of poly1, all in poly1's frame (xf maps poly2's frame
/// into poly1's): every edge of poly1 is scanned and ties keep the lowest edge index. Separations
/// are exact Q32.32 dot products.
Wide ScannedMaxSeparation(int32* edgeIndex, const b2PolygonShape* poly1, const b2PolygonShape* poly2,
                          const b2Transform& xf);

/// ScannedMaxSeparation's edge and separation, in closed form when both polygons are centred
/// boxes within the ranges where it gives the scan's bits (CentredBox.h), by the scan otherwise.
Wide MaxSeparation(int32* edgeIndex, const b2PolygonShape* poly1, const b2PolygonShape* poly2, const b2Transform& xf);

}  // namespace lockbox::collision_detail
