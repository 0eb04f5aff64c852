// The polygon collision's separating-axis search for two centred boxes, in closed form, against
// the scan over every edge that defines it: the same edge, the same exact separation and the
// same saturation reports, for boxes of every size, rotations that are unit, exact axes or any
// pair in range, and offsets up to and beyond the closed form's range (where the scan runs).
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "collision/MaxSeparation.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using collision_detail::MaxSeparation;
using collision_detail::ScannedMaxSeparation;

// A raw of `bits` random bits at most, either sign.
int32 RawOfWidth(std::mt19937_64& rng, int bits) {
    const auto magnitude = static_cast<int32>(rng() >> (64 - bits));
    return (rng() & 1) != 0 ? -magnitude : magnitude;
}

// Compares the two searches for one pair; returns false (with a test failure) on a difference.
bool SameAsScan(const b2PolygonShape& poly1, const b2PolygonShape& poly2, const b2Transform& xf) {
    int32 scannedEdge = -1, edge = -1;
    ResetSaturationCount();
    const Wide scanned = ScannedMaxSeparation(&scannedEdge, &poly1, &poly2, xf);
    const uint64_t scannedReports = SaturationCount();
    ResetSaturationCount();
    const Wide separation = MaxSeparation(&edge, &poly1, &poly2, xf);
    const uint64_t reports = SaturationCount();
    ResetSaturationCount();
    EXPECT_EQ(edge, scannedEdge) << "q " << xf.q.c.Raw() << "," << xf.q.s.Raw() << " p " << xf.p.x.Raw() << ","
                                 << xf.p.y.Raw();
    EXPECT_EQ(separation.Raw(), scanned.Raw())
        << "q " << xf.q.c.Raw() << "," << xf.q.s.Raw() << " p " << xf.p.x.Raw() << "," << xf.p.y.Raw();
    EXPECT_EQ(reports, scannedReports);
    return edge == scannedEdge && separation.Raw() == scanned.Raw() && reports == scannedReports;
}

TEST(MaxSeparation, TwoBoxesGiveTheScansEdgeAndSeparation) {
    std::mt19937_64 rng(0x5e9a);
    // Checked builds trap on a saturation instead of counting it: there the pairs stay within the
    // closed form's ranges, where the scan cannot saturate.
    const bool inRangeOnly = kOverflowTraps;
    int compared = 0;
    for (int trial = 0; trial < 200000; ++trial) {
        // Half-extents of every length a valid box has, up to 2^28 raw (4096 m; the closed form
        // takes them below 2^27). Boxes much below a linear slop are not valid polygons.
        const auto extent = [&] {
            const int bits = 10 + static_cast<int>(rng() % (inRangeOnly ? 17 : 19));
            return Fixed::FromRaw(static_cast<int32>(1 + (rng() >> (64 - bits))));
        };
        b2PolygonShape box1, box2;
        if (box1.SetAsBox(extent(), extent()) != b2ShapeError::ok) continue;
        if (box2.SetAsBox(extent(), extent()) != b2ShapeError::ok) continue;

        b2Transform xf;
        switch (trial % (inRangeOnly ? 3 : 4)) {
            case 0:  // a unit rotation from an angle
                xf.q = b2Rot(Fixed::FromRaw(RawOfWidth(rng, 19)));
                break;
            case 1: {  // the exact axes and half-turns: every zero component ties two corners
                const int32 axes[4][2] = {{65536, 0}, {0, 65536}, {-65536, 0}, {0, -65536}};
                const auto& a = axes[rng() % 4];
                xf.q.c = Fixed::FromRaw(a[0]);
                xf.q.s = Fixed::FromRaw(a[1]);
                break;
            }
            case 2:  // any pair of components up to one, zeros included
                xf.q.c = Fixed::FromRaw(trial % 9 == 0 ? 0 : RawOfWidth(rng, 17) / 2);
                xf.q.s = Fixed::FromRaw(trial % 13 == 0 ? 0 : RawOfWidth(rng, 17) / 2);
                break;
            default:  // components up to two: beyond one the scan decides
                xf.q.c = Fixed::FromRaw(RawOfWidth(rng, 18));
                xf.q.s = Fixed::FromRaw(RawOfWidth(rng, 18));
                break;
        }
        // Offsets of every length up to 2^30 raw (the closed form takes them below 2^29).
        const int offsetBits = inRangeOnly ? 29 : 30;
        xf.p.x = Fixed::FromRaw(RawOfWidth(rng, 1 + static_cast<int>(rng() % offsetBits)));
        xf.p.y = Fixed::FromRaw(RawOfWidth(rng, 1 + static_cast<int>(rng() % offsetBits)));
        ASSERT_TRUE(SameAsScan(box1, box2, xf)) << "trial " << trial;
        ASSERT_TRUE(SameAsScan(box2, box1, xf)) << "trial " << trial;
        ++compared;
    }
    EXPECT_GT(compared, 150000);
}

TEST(MaxSeparation, TouchingAndOverlappingBoxesAtTheRangesEdges) {
    // Boxes that touch or overlap, as the collision sees them, with offsets and half-extents at
    // and next to the closed form's limits.
    std::mt19937_64 rng(0x70c4);
    const int32 halves[] = {1, 2, 65536, (1 << 27) - 1, 1 << 27};
    const int32 offsets[] = {0, 1, -1, (1 << 29) - 1, -((1 << 29) - 1), 1 << 29, -(1 << 29)};
    for (const int32 h1 : halves) {
        for (const int32 h2 : halves) {
            b2PolygonShape box1, box2;
            if (box1.SetAsBox(Fixed::FromRaw(h1), Fixed::FromRaw(h2)) != b2ShapeError::ok) continue;
            if (box2.SetAsBox(Fixed::FromRaw(h2), Fixed::FromRaw(h1)) != b2ShapeError::ok) continue;
            for (const int32 ox : offsets) {
                for (const int32 oy : offsets) {
                    for (int k = 0; k < 8; ++k) {
                        b2Transform xf;
                        xf.q = b2Rot(Fixed::FromRaw(static_cast<int32>(rng() % 411775) - 205887));
                        if (k == 0) xf.q = b2Rot();
                        xf.p = b2Vec2(Fixed::FromRaw(ox), Fixed::FromRaw(oy));
                        ASSERT_TRUE(SameAsScan(box1, box2, xf));
                    }
                }
            }
        }
    }
}

TEST(MaxSeparation, BoxesWithOtherNormalsTakeTheScan) {
    // The vertices of a centred box with a normal edited by hand: the closed form would assume
    // the axis, the scan reads the normal. Both must agree with the scan.
    b2PolygonShape box1, box2;
    ASSERT_EQ(box1.SetAsBox(Fixed(1), Fixed(2)), b2ShapeError::ok);
    ASSERT_EQ(box2.SetAsBox(Fixed(0.5), Fixed(0.5)), b2ShapeError::ok);
    box1.m_normals[1] = b2Vec2(Fixed::FromRaw(65535), Fixed::FromRaw(362));
    b2Transform xf;
    xf.q = b2Rot(Fixed(0.3));
    xf.p = b2Vec2(Fixed(1.4), Fixed(0.2));
    EXPECT_TRUE(SameAsScan(box1, box2, xf));
    int32 edge = -1;
    const Wide separation = MaxSeparation(&edge, &box1, &box2, xf);
    b2PolygonShape clean;
    ASSERT_EQ(clean.SetAsBox(Fixed(1), Fixed(2)), b2ShapeError::ok);
    int32 cleanEdge = -1;
    const Wide cleanSeparation = MaxSeparation(&cleanEdge, &clean, &box2, xf);
    // The edited normal leans into box2's corner, so its edge reports another separation.
    EXPECT_NE(separation.Raw(), cleanSeparation.Raw());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
