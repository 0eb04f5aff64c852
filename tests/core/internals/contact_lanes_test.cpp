// The contact solver solves one colour's contacts four at a time in integer lanes where the
// machine has them (x86-64 with AVX2). The lanes stand for the scalar row and must give its
// bits: the same velocities, the same accumulated impulses and the same saturation count, on
// random rows across every magnitude (the lanes hand the rows they cannot follow back to the
// scalar row) and on worlds whose large islands are coloured.

#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "../dynamics/DynamicsTestUtil.h"
#include "LaneValues.h"
#include "dynamics/contacts/ContactSolver.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

// Restores the lanes when a test ends, whatever it switched.
struct LanesAllowed {
    ~LanesAllowed() { b2ContactSolver::AllowLanes(true); }
};

// Random rows of one colour: row i writes bodies 2i + 1 and 2i + 2 (or only one of them when the
// other is body 0, a static body several rows read). Raws are mostly of a game's magnitudes,
// and sometimes anywhere in the 64-bit range, where the scalar row saturates.
class RowMaker : public test::LaneValues {
public:
    explicit RowMaker(uint32_t seed) : LaneValues(seed) {}

    void Fill(b2ContactVelocityConstraint& vc, int32 row, int32 pointCount) {
        vc = b2ContactVelocityConstraint();
        const bool staticA = Pick(6) == 0;
        vc.indexA = staticA ? 0 : 2 * row + 1;
        vc.indexB = 2 * row + 2;
        vc.pointCount = pointCount;
        vc.contactIndex = row;
        const double angle = Uniform(0, 6.283);
        vc.normal = b2Vec2(Fixed::FromRaw(static_cast<int32_t>(std::cos(angle) * 65536)),
                           Fixed::FromRaw(static_cast<int32_t>(std::sin(angle) * 65536)));
        if (Pick(30) == 0) vc.normal = b2Vec2(FixedValue(1), FixedValue(1));
        vc.tangent = b2Cross(vc.normal, Fixed(1));
        vc.invMassA = staticA ? Wide() : Positive(0.05, 2);
        vc.invIA = staticA ? Wide() : Positive(0.1, 8);
        vc.invMassB = Positive(0.05, 2);
        vc.invIB = Pick(10) == 0 ? Wide() : Positive(0.1, 8);
        vc.pushA = b2WideVec2(vc.invMassA * vc.normal.x, vc.invMassA * vc.normal.y);
        vc.pushB = b2WideVec2(vc.invMassB * vc.normal.x, vc.invMassB * vc.normal.y);
        if (Pick(20) == 0) vc.pushB = b2WideVec2(WideValue(2), WideValue(2));
        vc.samePush = vc.pushA.x == vc.pushB.x && vc.pushA.y == vc.pushB.y;
        vc.friction = Pick(8) == 0 ? FixedValue(1) : Fixed::FromRaw(static_cast<int32_t>(Uniform(0, 1) * 65536));
        vc.K = {Positive(0.1, 4), WideValue(2), Positive(0.1, 4)};
        vc.normalMass = {Positive(0.1, 4), WideValue(1), Positive(0.1, 4)};
        vc.useBlock = pointCount == 2;
        for (int32 j = 0; j < pointCount; ++j) {
            b2VelocityConstraintPoint& p = vc.points[j];
            p.normalImpulse = Pick(5) == 0 ? Wide() : WideValue(0.5);
            if (p.normalImpulse < Wide() && Pick(2) == 0) p.normalImpulse = -p.normalImpulse;
            p.tangentImpulse = WideValue(0.2);
            p.normalMass = Positive(0.1, 4);
            p.tangentMass = Positive(0.1, 4);
            p.rnA = FixedValue(1);
            p.rnB = FixedValue(1);
            p.rtA = FixedValue(1);
            p.rtB = FixedValue(1);
            p.turnNA = staticA ? Wide() : WideValue(4);
            p.turnNB = WideValue(4);
            p.turnTA = staticA ? Wide() : WideValue(4);
            p.turnTB = WideValue(4);
            p.velocityBias = Pick(4) == 0 ? Fixed::FromRaw(static_cast<int32_t>(Uniform(0, 2) * 65536)) : Fixed();
        }
    }
};

struct SolveResult {
    std::vector<b2Velocity> velocities;
    std::vector<b2ContactVelocityConstraint> constraints;
    uint64_t saturations = 0;
    int64_t inLanes = 0;  ///< rows the lanes solved, over all iterations
};

// Solves one colour `iterations` times; its set-up and each iteration run over the ranges that
// `cuts` (ascending, inside the colour) divide it into, as workers' blocks divide a colour.
SolveResult SolveColour(std::vector<b2ContactVelocityConstraint> constraints, std::vector<b2Velocity> velocities,
                        bool lanes, int iterations, std::vector<int32> cuts = {}) {
    b2ContactSolver::AllowLanes(lanes);
    b2ContactSolverDef def;
    def.count = static_cast<int32>(constraints.size());
    def.velocities = velocities.data();
    def.velocityConstraints = constraints.data();
    std::vector<b2LaneQuad> laneRows(b2ContactSolver::LaneRowsSize(def.count));
    def.laneRows = laneRows.data();
    b2ContactSolver solver(&def);
    cuts.insert(cuts.begin(), 0);
    cuts.push_back(def.count);
    for (size_t r = 0; r + 1 < cuts.size(); ++r) solver.StoreLaneRows(cuts[r], cuts[r + 1]);
    SolveResult result;
    {
        const SaturationCapture capture(&result.saturations);
        for (int i = 0; i < iterations; ++i) {
            for (size_t r = 0; r + 1 < cuts.size(); ++r)
                result.inLanes += solver.SolveIndependentVelocityConstraints(cuts[r], cuts[r + 1]);
        }
    }
    result.velocities = std::move(velocities);
    result.constraints = std::move(constraints);
    return result;
}

TEST(ContactLanes, RandomRowsGiveTheScalarRowsBits) {
    if (!b2ContactSolver::LanesAvailable())
        GTEST_SKIP() << "no integer lanes on this machine: only the scalar row runs";
    const LanesAllowed restore;
    const test::QuietTraps quiet;
    int64_t lanesTotal = 0;
    for (uint32_t seed = 1; seed <= 40; ++seed) {
        RowMaker make(seed);
        constexpr int32 kRows = 512;
        std::vector<b2ContactVelocityConstraint> constraints(kRows);
        int32 pointCount = 2;
        for (int32 i = 0; i < kRows; ++i) {
            // Runs of equal point counts (the lanes take four alike) broken at random.
            if (make.Pick(7) == 0) pointCount = 3 - pointCount;
            make.Fill(constraints[static_cast<size_t>(i)], i, pointCount);
        }
        std::vector<b2Velocity> velocities(2 * kRows + 1);
        for (b2Velocity& v : velocities) {
            v.v = b2WideVec2(make.WideValue(8), make.WideValue(8));
            v.w = make.WideValue(6);
        }

        // Odd seeds cut the colour into ranges at random places, most not on a multiple of four.
        const std::vector<int32> cuts = seed % 2 == 1 ? make.Cuts(kRows) : std::vector<int32>{};
        const SolveResult lanes = SolveColour(constraints, velocities, true, 8, cuts);
        const SolveResult scalar = SolveColour(constraints, velocities, false, 8);
        EXPECT_EQ(scalar.inLanes, 0);
        lanesTotal += lanes.inLanes;
        ASSERT_EQ(lanes.saturations, scalar.saturations) << "seed " << seed;
        ASSERT_TRUE(test::SameVelocities(lanes.velocities, scalar.velocities)) << "seed " << seed;
        for (size_t i = 0; i < constraints.size(); ++i) {
            for (int32 j = 0; j < constraints[i].pointCount; ++j) {
                ASSERT_EQ(lanes.constraints[i].points[j].normalImpulse, scalar.constraints[i].points[j].normalImpulse)
                    << "seed " << seed << " row " << i << " point " << j;
                ASSERT_EQ(lanes.constraints[i].points[j].tangentImpulse, scalar.constraints[i].points[j].tangentImpulse)
                    << "seed " << seed << " row " << i << " point " << j;
            }
        }
    }
    // Both paths were taken: some rows in the lanes, the rest by the scalar row.
    EXPECT_GT(lanesTotal, 0);
    EXPECT_LT(lanesTotal, int64_t{40} * 8 * 512);
}

// Rows of a game's magnitudes mostly stay in the lanes; the test above would pass with none.
TEST(ContactLanes, ResolvedWorldRowsStayInTheLanes) {
    if (!b2ContactSolver::LanesAvailable()) GTEST_SKIP() << "no integer lanes on this machine";
    const LanesAllowed restore;
    // A resting two-point row: both points pushing, the lanes' case.
    b2ContactVelocityConstraint vc;
    vc.indexA = 0;
    vc.pointCount = 2;
    vc.normal = b2Vec2(0, 1);
    vc.tangent = b2Cross(vc.normal, Fixed(1));
    vc.invMassB = Wide(1);
    vc.invIB = Wide(6);
    vc.pushB = b2WideVec2(Wide(), Wide(1));
    vc.friction = Fixed::FromRatio(6, 10);
    vc.K = {Wide(2), Wide(-1), Wide(2)};
    vc.normalMass = {Wide::FromRatio(2, 3), Wide::FromRatio(1, 3), Wide::FromRatio(2, 3)};
    for (int32 j = 0; j < 2; ++j) {
        vc.points[j].normalMass = Wide::FromRatio(1, 2);
        vc.points[j].tangentMass = Wide(1);
        vc.points[j].rnB = Fixed::FromRatio(j == 0 ? -1 : 1, 2);
        vc.points[j].turnNB = Wide(6) * vc.points[j].rnB;
        vc.points[j].rtB = Fixed::FromRatio(1, 2);
        vc.points[j].turnTB = Wide(3);
        vc.points[j].normalImpulse = Wide::FromRatio(1, 12);
    }
    std::vector<b2ContactVelocityConstraint> constraints(8, vc);
    std::vector<b2Velocity> velocities(9);
    for (int32 i = 0; i < 8; ++i) {
        constraints[static_cast<size_t>(i)].indexB = i + 1;
        velocities[static_cast<size_t>(i + 1)].v = b2WideVec2(Wide(), -Wide::FromRatio(1, 6));
    }
    const SolveResult lanes = SolveColour(constraints, velocities, true, 1);
    const SolveResult scalar = SolveColour(constraints, velocities, false, 1);
    EXPECT_EQ(lanes.inLanes, 8);
    for (size_t b = 1; b < velocities.size(); ++b) {
        EXPECT_EQ(lanes.velocities[b].v.y, scalar.velocities[b].v.y);
        EXPECT_EQ(lanes.velocities[b].w, scalar.velocities[b].w);
        // The row acted: the body no longer sinks.
        EXPECT_GT(scalar.velocities[b].v.y, velocities[b].v.y);
    }
}

// The hashes of 90 steps of a pyramid of boxes, one island of well over a thousand contacts (so
// coloured), dropped from a height so that its contacts take every case of the block solver
// while it lands.
std::vector<uint64_t> Hashes(bool lanes) {
    b2ContactSolver::AllowLanes(lanes);
    b2World world(b2Vec2(0, -10));
    test::MakeBoxPyramid(world, 40, 150, 101);
    return test::StepHashes(world, 90);
}

TEST(ContactLanes, ColouredIslandGivesTheSameHashes) {
    const LanesAllowed restore;
    EXPECT_EQ(Hashes(true), Hashes(false));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
