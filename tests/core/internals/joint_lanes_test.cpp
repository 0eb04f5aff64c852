// The joint solver solves one colour's revolute point rows four at a time in integer lanes where
// the machine has them (x86-64 with AVX2). The lanes stand for the scalar row and must give its
// bits: the same velocities, the same accumulated impulses and the same saturation count, on
// random rows across every magnitude (the lanes hand the rows they cannot follow back to the
// scalar row) and on worlds whose joint islands are coloured, with one worker or several.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "../dynamics/DynamicsTestUtil.h"
#include "LaneValues.h"
#include "dynamics/joints/JointSolver.h"
#include "dynamics/lanes/IntegerLanes.h"
#include "lockbox/dynamics/joints/DistanceJoint.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using JointSolver = core_detail::Engine::Joints::Solver;

// Restores the lanes when a test ends, whatever it switched.
struct Restore {
    ~Restore() { lanes::Allow(true); }
};

bool LanesAvailable() {
#ifdef LOCKBOX_INTEGER_LANES
    return lanes::HasAvx2();
#else
    return false;
#endif
}

// Random point rows of one colour: row i joins bodies 2i and 2i + 1. Raws are mostly of a game's
// magnitudes, and sometimes anywhere in their range, where the scalar row saturates; arms are
// sometimes beyond the lanes' 2^30 raw.
class RowMaker : public test::LaneValues {
public:
    explicit RowMaker(uint32_t seed) : LaneValues(seed) {}

    // Mostly in [lo, hi), sometimes any raw.
    Wide Mass(double lo, double hi) { return Pick(30) == 0 ? WideValue(1) : Positive(lo, hi); }

    void Fill(JointSolver::Row& row, int32 i, b2RevoluteJoint* joint) {
        row = JointSolver::Row();
        row.indexA = 2 * i;
        row.indexB = 2 * i + 1;
        row.rA = b2Vec2(FixedValue(2), FixedValue(2));
        row.rB = b2Vec2(FixedValue(2), FixedValue(2));
        row.mA = Mass(0.05, 2);
        row.mB = Mass(0.05, 2);
        row.iA = Mass(0.1, 8);
        row.iB = Mass(0.1, 8);
        row.pointMass = b2WideMat22{b2WideVec2(Mass(0.1, 4), WideValue(1)), b2WideVec2(WideValue(1), Mass(0.1, 4))};
        row.impulse = b2WideVec2(WideValue(0.5), WideValue(0.5));
        row.joint = joint;
        row.revolute = joint;
        // Most rows carry the widths their set-up would give them (the unchecked scalar row);
        // some none (the tested scalar row).
        if (Pick(4) != 0) row.unchecked = JointSolver::PointRowWidths(row);
    }
};

struct SolveResult {
    std::vector<b2Velocity> velocities;
    std::vector<b2WideVec2> impulses;
    uint64_t saturations = 0;
    int64_t inLanes = 0;  ///< rows the lanes solved, over all iterations
};

// Solves one colour `iterations` times over the ranges that `cuts` (ascending, inside the colour)
// divide it into, as workers' blocks divide a colour.
SolveResult SolveColour(const std::vector<JointSolver::Row>& rows, std::vector<b2Velocity> velocities, bool withLanes,
                        int iterations, std::vector<int32> cuts = {}) {
    lanes::Allow(withLanes);
    JointSolver solver;
    const auto count = static_cast<int32>(rows.size());
    solver.Begin(count);
    std::copy(rows.begin(), rows.end(), solver.Rows().begin());
    b2SolverData data;
    data.velocities = velocities.data();
    cuts.insert(cuts.begin(), 0);
    cuts.push_back(count);
    SolveResult result;
    {
        const SaturationCapture capture(&result.saturations);
        for (int i = 0; i < iterations; ++i) {
            for (size_t r = 0; r + 1 < cuts.size(); ++r)
                result.inLanes += solver.SolveIndependentVelocityConstraints(data, cuts[r], cuts[r + 1]);
        }
    }
    result.velocities = std::move(velocities);
    for (const JointSolver::Row& row : solver.Rows()) result.impulses.push_back(row.impulse);
    return result;
}

// A revolute joint for the rows to name (their iterations never read it).
struct HostJoint {
    b2World world{b2Vec2(0, 0)};
    b2RevoluteJoint* joint = nullptr;
    HostJoint() {
        b2Body* a = test::MakeDynamicBox(world, 0, 0, 1, 1);
        b2Body* b = test::MakeDynamicBox(world, 2, 0, 1, 1);
        b2RevoluteJointDef def;
        def.Initialize(a, b, b2Vec2(1, 0));
        joint = static_cast<b2RevoluteJoint*>(world.CreateJoint(&def));
    }
};

TEST(JointLanes, RandomRowsGiveTheScalarRowsBits) {
    if (!LanesAvailable()) GTEST_SKIP() << "no integer lanes on this machine: only the scalar row runs";
    const Restore restore;
    const test::QuietTraps quiet;
    const HostJoint host;
    constexpr int32 kRows = 512;
    constexpr int kSeeds = 40, kIterations = 8;
    int64_t lanesTotal = 0;
    for (uint32_t seed = 1; seed <= kSeeds; ++seed) {
        RowMaker make(seed);
        std::vector<JointSolver::Row> rows(kRows);
        for (int32 i = 0; i < kRows; ++i) make.Fill(rows[static_cast<size_t>(i)], i, host.joint);
        std::vector<b2Velocity> velocities(2 * kRows);
        for (b2Velocity& v : velocities) {
            v.v = b2WideVec2(make.WideValue(8), make.WideValue(8));
            v.w = make.WideValue(6);
        }
        // Odd seeds cut the colour into ranges at random places, most not on a multiple of four.
        const std::vector<int32> cuts = seed % 2 == 1 ? make.Cuts(kRows) : std::vector<int32>{};
        const SolveResult withLanes = SolveColour(rows, velocities, true, kIterations, cuts);
        const SolveResult scalar = SolveColour(rows, velocities, false, kIterations);
        EXPECT_EQ(scalar.inLanes, 0);
        lanesTotal += withLanes.inLanes;
        ASSERT_EQ(withLanes.saturations, scalar.saturations) << "seed " << seed;
        ASSERT_TRUE(test::SameVelocities(withLanes.velocities, scalar.velocities)) << "seed " << seed;
        for (size_t i = 0; i < rows.size(); ++i) {
            ASSERT_EQ(withLanes.impulses[i].x, scalar.impulses[i].x) << "seed " << seed << " row " << i;
            ASSERT_EQ(withLanes.impulses[i].y, scalar.impulses[i].y) << "seed " << seed << " row " << i;
        }
    }
    // Both paths were taken: a good share of the rows in the lanes (the random extremes send
    // many to the scalar row, and a row that grew beyond the bound stays there), the rest by the
    // scalar row.
    EXPECT_GT(lanesTotal, int64_t{kSeeds} * kIterations * kRows / 20);
    EXPECT_LT(lanesTotal, int64_t{kSeeds} * kIterations * kRows);
}

// Rows of a game's magnitudes stay in the lanes; the test above would pass with none.
TEST(JointLanes, GameRowsStayInTheLanes) {
    if (!LanesAvailable()) GTEST_SKIP() << "no integer lanes on this machine";
    const Restore restore;
    const HostJoint host;
    std::vector<JointSolver::Row> rows(8);
    std::vector<b2Velocity> velocities(16);
    for (int32 i = 0; i < 8; ++i) {
        JointSolver::Row& row = rows[static_cast<size_t>(i)];
        row.indexA = 2 * i;
        row.indexB = 2 * i + 1;
        row.rA = b2Vec2(Fixed::FromRatio(1, 2), Fixed::FromRatio(-1, 4));
        row.rB = b2Vec2(Fixed::FromRatio(-1, 2), Fixed::FromRatio(1, 4));
        row.mA = row.mB = Wide::FromRatio(1, 2);
        row.iA = row.iB = Wide(6);
        row.pointMass = b2WideMat22{b2WideVec2(Wide::FromRatio(2, 3), Wide::FromRatio(1, 5)),
                                    b2WideVec2(Wide::FromRatio(1, 5), Wide::FromRatio(3, 4))};
        row.impulse = b2WideVec2(Wide::FromRatio(1, 100), Wide::FromRatio(-3, 100));
        row.joint = row.revolute = host.joint;
        row.unchecked = JointSolver::PointRowWidths(row);
        velocities[static_cast<size_t>(2 * i)].v = b2WideVec2(Wide::FromRatio(i, 7), -Wide::FromRatio(1, 6));
        velocities[static_cast<size_t>(2 * i + 1)].w = Wide::FromRatio(-i, 3);
    }
    const SolveResult withLanes = SolveColour(rows, velocities, true, 1);
    const SolveResult scalar = SolveColour(rows, velocities, false, 1);
    EXPECT_EQ(withLanes.inLanes, 8);
    for (size_t b = 0; b < velocities.size(); ++b) {
        EXPECT_EQ(withLanes.velocities[b].v.x, scalar.velocities[b].v.x);
        EXPECT_EQ(withLanes.velocities[b].v.y, scalar.velocities[b].v.y);
        EXPECT_EQ(withLanes.velocities[b].w, scalar.velocities[b].w);
    }
    // The rows acted: every body's velocity changed.
    for (size_t b = 0; b < velocities.size(); ++b) {
        const bool moved = scalar.velocities[b].v.x != velocities[b].v.x ||
                           scalar.velocities[b].v.y != velocities[b].v.y || scalar.velocities[b].w != velocities[b].w;
        EXPECT_TRUE(moved) << "body " << b;
    }
}

// The hashes of 60 steps of a hanging net of boxes: one island of 1,984 joints (so
// coloured), mostly idle revolute joints (the lanes' rows), with some motors, limits and distance
// joints among them (joints solved by themselves inside the colours), falling onto a ground box.
std::vector<uint64_t> NetHashes(bool withLanes, int32 workers) {
    lanes::Allow(withLanes);
    b2World world(b2Vec2(0, -10));
    if (workers > 1) world.SetWorkerCount(workers);
    test::MakeStaticBox(world, 0, -20, 40, 1);
    constexpr int kSide = 32;
    std::vector<b2Body*> bodies;
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x)
            bodies.push_back(test::MakeDynamicBox(world, Fixed(x) - 16, Fixed(y), Fixed::FromRatio(2, 5),
                                                  Fixed::FromRatio(2, 5), Fixed(1 + (x + y) % 3)));
    }
    int made = 0;
    auto link = [&](b2Body* a, b2Body* b) {
        const b2Vec2 mid = Fixed::FromRatio(1, 2) * (a->GetPosition() + b->GetPosition());
        if (++made % 17 == 0) {
            b2DistanceJointDef def;
            def.Initialize(a, b, a->GetPosition(), b->GetPosition());
            world.CreateJoint(&def);
            return;
        }
        b2RevoluteJointDef def;
        def.Initialize(a, b, mid);
        def.enableMotor = made % 23 == 0;
        def.maxMotorTorque = 5;
        def.motorSpeed = 1;
        def.enableLimit = made % 29 == 0;
        def.lowerAngle = Fixed::FromRatio(-1, 4);
        def.upperAngle = Fixed::FromRatio(1, 4);
        world.CreateJoint(&def);
    };
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) {
            b2Body* b = bodies[static_cast<size_t>(y * kSide + x)];
            if (x + 1 < kSide) link(b, bodies[static_cast<size_t>(y * kSide + x + 1)]);
            if (y + 1 < kSide) link(b, bodies[static_cast<size_t>((y + 1) * kSide + x)]);
        }
    }
    return test::StepHashes(world, 60);
}

TEST(JointLanes, ColouredJointIslandGivesTheSameHashes) {
    const Restore restore;
    const std::vector<uint64_t> scalar = NetHashes(false, 1);
    EXPECT_EQ(NetHashes(true, 1), scalar);
    EXPECT_EQ(NetHashes(true, 2), scalar);
    // The net moved: its hash changed over the steps.
    EXPECT_NE(scalar.front(), scalar.back());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
