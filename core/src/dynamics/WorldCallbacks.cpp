// The default contact filter (the manual's "Filtering" rule).
#include "lockbox/dynamics/WorldCallbacks.h"

#include "lockbox/dynamics/Fixture.h"

namespace lockbox {

bool b2ContactFilter::ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB) {
    const b2Filter& filterA = fixtureA->GetFilterData();
    const b2Filter& filterB = fixtureB->GetFilterData();
    // A shared non-zero group overrides the category bits: positive always, negative never.
    if (filterA.groupIndex == filterB.groupIndex && filterA.groupIndex != 0) return filterA.groupIndex > 0;
    return (filterA.maskBits & filterB.categoryBits) != 0 && (filterA.categoryBits & filterB.maskBits) != 0;
}

}  // namespace lockbox
