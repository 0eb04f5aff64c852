// Full differential run of b2Distance and b2TimeOfImpact against float Box2D 2.4.1: 10,000
// seeded random pairs per pair type (the fast suite runs 500). The test body, the generators
// and the disagreement classes are those of ../distance_diff_test.cpp, included here so that
// both suites always check the same thing.

#define LOCKBOX_DISTANCE_DIFF_PAIRS 10000
#define LOCKBOX_DISTANCE_DIFF_SUITE DistanceDiffHeavy
#define LOCKBOX_TOI_DIFF_SUITE ToiDiffHeavy
#include "../distance_diff_test.cpp"
