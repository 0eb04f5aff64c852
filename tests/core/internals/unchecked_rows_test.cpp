// A solver row whose inputs are within the widths its set-up computed runs without range tests
// (dynamics/unchecked/Widths.h): a contact row (ContactRowBound.h), a joint's point row or its
// position row (JointSolver.h). That must give the tested row's bits: the same velocities (or
// positions), impulses and saturation count. Rows are drawn with constants of every scale and inputs driven to just
// inside and just outside their bound; within it, the tested row must never saturate (the bound is sound). And the
// inputs must reach the bound's edge: with the bound loosened by a few bits the unchecked row must go wrong somewhere,
// or these tests could not fail.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../dynamics/DynamicsTestUtil.h"
#include "dynamics/contacts/ContactPointSetUp.h"
#include "dynamics/contacts/ContactPointSetUpBound.h"
#include "dynamics/contacts/ContactPositionBound.h"
#include "dynamics/contacts/ContactPositionRow.h"
#include "dynamics/contacts/ContactRowBound.h"
#include "dynamics/contacts/ContactSolver.h"
#include "dynamics/joints/JointMath.h"
#include "dynamics/joints/JointSolver.h"
#include "dynamics/unchecked/UncheckedWide.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using JointSolver = core_detail::Engine::Joints::Solver;

// The rows saturate on purpose: a checked build, which traps on overflow, is told to go on with
// the saturated result (and still counts it) while this is alive.
struct QuietTraps {
    OverflowTrapHandler previous = SetOverflowTrapHandler([](const char*, int64_t, int64_t) {});
    ~QuietTraps() { SetOverflowTrapHandler(previous); }
};

// Restores the unchecked rows when a test ends, whatever it switched.
struct UncheckedAllowed {
    ~UncheckedAllowed() { solver::AllowUncheckedRows(true); }
};

class RowDrawer {
public:
    explicit RowDrawer(uint64_t seed) : m_rng(seed) {}

    int Pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(m_rng); }
    bool Chance(int oneIn) { return Pick(1, oneIn) == 1; }

    // A raw of width at most `width` (|raw| < 2^width), often at the top of that range, either sign.
    int64_t Raw(int width) {
        width = std::clamp(width, 0, 63);
        if (width == 0) return 0;
        const uint64_t top = (uint64_t{1} << width) - 1;
        uint64_t mag = m_rng() & top;
        if (Chance(2)) mag |= uint64_t{1} << (width - 1);  // exactly this width
        if (Chance(4)) mag = top;                          // the widest
        const auto v = static_cast<int64_t>(mag);
        return Chance(2) ? -v : v;
    }
    Wide WideOf(int width) { return Wide::FromRaw(Raw(width)); }
    Fixed FixedOf(int width) { return Fixed::FromRaw(static_cast<int32_t>(Raw(std::min(width, 31)))); }

    // A unit direction at any angle or, one time in `oneIn`, a vector of any size.
    b2Vec2 Direction(int oneIn) {
        const double angle = Pick(0, 6283) / 1000.0;
        return Chance(oneIn) ? b2Vec2(FixedOf(Pick(1, 31)), FixedOf(Pick(1, 31)))
                             : b2Vec2(Fixed::FromRaw(static_cast<int32_t>(std::cos(angle) * 65536)),
                                      Fixed::FromRaw(static_cast<int32_t>(std::sin(angle) * 65536)));
    }

    // Constants of every scale: effective masses around 2^massScale kg, responses (pushes, turns,
    // K) around their inverse, with the spread a row of mismatched bodies has.
    void Fill(b2ContactVelocityConstraint& vc) {
        vc = b2ContactVelocityConstraint();
        vc.pointCount = Pick(1, 2);
        vc.useBlock = vc.pointCount == 2;
        vc.indexA = 0;
        vc.indexB = 1;
        const int mass = 32 + Pick(-14, 14);
        const int resp = 64 - mass + Pick(-3, 9);
        const int arm = Chance(3) ? Pick(1, 31) : Pick(12, 19);
        vc.normal = Direction(8);
        vc.tangent = b2Cross(vc.normal, Fixed(1));
        const bool staticA = Chance(5);
        vc.invMassA = staticA ? Wide() : WideOf(resp);
        vc.invIA = staticA ? Wide() : WideOf(resp);
        vc.invMassB = WideOf(resp);
        vc.invIB = WideOf(resp);
        vc.pushA = staticA ? b2WideVec2() : b2WideVec2(WideOf(resp), WideOf(resp));
        vc.pushB = b2WideVec2(WideOf(resp), WideOf(resp));
        if (Chance(4)) vc.pushB = vc.pushA;
        vc.samePush = vc.pushA.x == vc.pushB.x && vc.pushA.y == vc.pushB.y;
        vc.friction = Chance(6) ? FixedOf(Pick(1, 31)) : FixedOf(17);
        vc.K = {WideOf(resp + 1), WideOf(resp + 1), WideOf(resp + 1)};
        vc.normalMass = {WideOf(mass + Pick(0, 4)), WideOf(mass + Pick(0, 4)), WideOf(mass + Pick(0, 4))};
        for (int32 j = 0; j < vc.pointCount; ++j) {
            b2VelocityConstraintPoint& p = vc.points[j];
            p.normalMass = WideOf(mass);
            p.tangentMass = WideOf(mass);
            p.rnA = FixedOf(arm);
            p.rnB = FixedOf(arm);
            p.rtA = FixedOf(arm);
            p.rtB = FixedOf(arm);
            p.turnNA = staticA ? Wide() : WideOf(resp);
            p.turnNB = WideOf(resp);
            p.turnTA = staticA ? Wide() : WideOf(resp);
            p.turnTB = WideOf(resp);
            p.velocityBias = Chance(3) ? FixedOf(Pick(1, 31)) : Fixed();
        }
    }

    // Inputs of width at most the given ones (velocities, impulses).
    void Inputs(b2ContactVelocityConstraint& vc, std::vector<b2Velocity>& bodies, int velocities, int impulses) {
        for (b2Velocity& b : bodies) {
            b.v = b2WideVec2(WideOf(velocities - Pick(0, 1)), WideOf(velocities - Pick(0, 1)));
            b.w = WideOf(velocities - Pick(0, 1));
        }
        if (vc.invMassA == Wide()) bodies[0] = b2Velocity();  // a static body does not move
        for (int32 j = 0; j < vc.pointCount; ++j) {
            vc.points[j].normalImpulse = WideOf(impulses - Pick(0, 1));
            vc.points[j].tangentImpulse = WideOf(impulses - Pick(0, 1));
        }
    }

private:
    std::mt19937_64 m_rng;
};

struct Solved {
    std::vector<b2Velocity> bodies;
    b2ContactVelocityConstraint vc;
    uint64_t saturations = 0;
};

Solved SolveOnce(b2ContactVelocityConstraint vc, std::vector<b2Velocity> bodies, bool unchecked) {
    solver::AllowUncheckedRows(unchecked);
    b2ContactSolverDef def;
    def.count = 1;
    def.velocities = bodies.data();
    def.velocityConstraints = &vc;
    b2ContactSolver solver(&def);
    Solved out;
    {
        const SaturationCapture capture(&out.saturations);
        solver.SolveVelocityConstraints(0, 1);
    }
    out.bodies = std::move(bodies);
    out.vc = vc;
    return out;
}

bool SameBits(const Solved& a, const Solved& b) {
    if (a.saturations != b.saturations) return false;
    for (size_t i = 0; i < a.bodies.size(); ++i) {
        if (a.bodies[i].v.x != b.bodies[i].v.x || a.bodies[i].v.y != b.bodies[i].v.y || a.bodies[i].w != b.bodies[i].w)
            return false;
    }
    for (int32 j = 0; j < a.vc.pointCount; ++j) {
        if (a.vc.points[j].normalImpulse != b.vc.points[j].normalImpulse ||
            a.vc.points[j].tangentImpulse != b.vc.points[j].tangentImpulse)
            return false;
    }
    return true;
}

// A width `bits` looser (a row with no width stays without).
uint8_t Loosened(uint8_t width, int bits) { return width == 0 ? 0 : static_cast<uint8_t>(std::min(width + bits, 63)); }

// What the trials of one kind of row found. A trial keeps the row's widths (loosen 0) or loosens
// them by a few bits on purpose.
class Tally {
public:
    static constexpr int kMaxLoosening = 12;

    // Judges one trial; false when it breaks the bound's promise (the caller stops there).
    bool Judge(int loosen, bool fits, bool same, uint64_t referenceSaturations) {
        if (loosen == 0) {
            (fits ? m_unchecked : m_tested) += 1;
            // Within the widths the tested row never saturates, and both paths agree.
            return same && (!fits || referenceSaturations == 0);
        }
        if (fits && !same) ++m_wrongWhenLoosened[loosen];
        return true;
    }

    // Both paths ran, and the inputs reached the bound's edge: widths a few bits looser let wrong
    // rows through.
    void Check(const char* rows) const {
        EXPECT_GT(m_unchecked, 5000);
        EXPECT_GT(m_tested, 5000);
        ASSERT_FALSE(m_wrongWhenLoosened.empty());
        std::printf("[ bound    ] %s unchecked %lld, tested %lld; wrong with the bound loosened by", rows,
                    static_cast<long long>(m_unchecked), static_cast<long long>(m_tested));
        for (const auto& [bits, count] : m_wrongWhenLoosened)
            std::printf(" %d bits: %lld,", bits, static_cast<long long>(count));
        std::printf("\n");
        EXPECT_LE(m_wrongWhenLoosened.begin()->first, 8);
    }

private:
    int64_t m_unchecked = 0, m_tested = 0;
    std::map<int, int64_t> m_wrongWhenLoosened;  // bits of loosening -> rows that went wrong
};

// How many bits a trial loosens its row's bound: none in half the trials, which keep the computed
// bound; the rest loosen it on purpose, to see that it matters.
int Loosening(RowDrawer& draw) { return draw.Chance(2) ? 0 : draw.Pick(1, Tally::kMaxLoosening); }

// Runs 60,000 trials of one kind of row on one drawer and one tally, each returning the tally's
// verdict on it, and then checks the tally.
template <class Trial>
void RunTrials(uint64_t seed, const char* rows, Trial trial) {
    const QuietTraps quiet;
    const UncheckedAllowed restore;
    RowDrawer draw(seed);
    Tally tally;
    for (int i = 0; i < 60000; ++i) ASSERT_TRUE(trial(draw, tally)) << rows << ", trial " << i;
    tally.Check(rows);
}

TEST(UncheckedRows, ContactRowsWithinTheBoundGiveTheTestedRowsBits) {
#ifndef LOCKBOX_UNCHECKED_ROWS
    GTEST_SKIP() << "no native 128-bit integer: every row keeps its tests";
#else
    int64_t bounded = 0;
    RunTrials(20261130, "contact rows", [&bounded](RowDrawer& draw, Tally& tally) {
        b2ContactVelocityConstraint vc;
        draw.Fill(vc);
        const solver::InputWidths widths = solver::UncheckedWidths(vc);
        const int loosen = Loosening(draw);
        vc.unchecked = {Loosened(widths.velocities, loosen), Loosened(widths.impulses, loosen)};
        const bool none = widths.velocities == 0 || widths.impulses == 0;
        if (!none) ++bounded;
        const int velocityWidth = none ? draw.Pick(16, 48) : vc.unchecked.velocities + draw.Pick(-3, 1);
        const int impulseWidth = none ? draw.Pick(16, 48) : vc.unchecked.impulses + draw.Pick(-3, 1);
        std::vector<b2Velocity> bodies(2);
        draw.Inputs(vc, bodies, velocityWidth, impulseWidth);

        const bool fits = solver::UncheckedRowFits(vc, bodies[0].v, bodies[0].w, bodies[1].v, bodies[1].w);
        const Solved fast = SolveOnce(vc, bodies, true);
        const Solved reference = SolveOnce(vc, bodies, false);
        return tally.Judge(loosen, fits, SameBits(fast, reference), reference.saturations);
    });
    // Most rows with a bound fit it.
    EXPECT_GT(bounded, 50000);
#endif
}

// A contact's velocity set-up: its manifold, the bodies' poses and velocities, and the constants
// Load copies from the bodies and the fixtures. The manifold lives in a contact of `world`.
struct SetUpCase {
    b2Manifold manifold;
    b2Position poses[2];
    b2Velocity velocities[2];
    b2ContactVelocityConstraint vc;
    b2ContactPositionConstraint pc;
};

// Draws a set-up's constants: arms, masses, inertias and restitution of every scale (now and
// then beyond the set-up's bound: a direction that is not unit, an arm or inertia too wide).
void FillSetUp(RowDrawer& draw, SetUpCase& c) {
    c = SetUpCase();
    b2Manifold& m = c.manifold;
    m.type = static_cast<b2Manifold::Type>(draw.Pick(0, 2));
    m.pointCount = m.type == b2Manifold::e_circles ? 1 : draw.Pick(1, 2);
    m.localNormal = draw.Direction(10);
    const int arm = draw.Chance(4) ? draw.Pick(1, 30) : draw.Pick(12, 20);
    m.localPoint = b2Vec2(draw.FixedOf(arm), draw.FixedOf(arm));
    for (int32 j = 0; j < m.pointCount; ++j)
        m.points[j].localPoint = b2Vec2(draw.FixedOf(arm - draw.Pick(0, 2)), draw.FixedOf(arm - draw.Pick(0, 2)));
    const int pose = draw.Chance(4) ? draw.Pick(1, 30) : draw.Pick(12, 24);
    for (b2Position& p : c.poses) {
        p.c = b2Vec2(draw.FixedOf(pose - draw.Pick(0, 1)), draw.FixedOf(pose - draw.Pick(0, 1)));
        p.a = draw.Chance(3) ? Fixed() : draw.FixedOf(draw.Pick(0, 20));
    }

    b2ContactPositionConstraint& pc = c.pc;
    pc.indexA = 0;
    pc.indexB = 1;
    pc.type = m.type;
    pc.pointCount = m.pointCount;
    pc.localCenterA = draw.Chance(2) ? b2Vec2() : b2Vec2(draw.FixedOf(arm - 2), draw.FixedOf(arm - 2));
    pc.localCenterB = draw.Chance(2) ? b2Vec2() : b2Vec2(draw.FixedOf(arm - 2), draw.FixedOf(arm - 2));
    pc.radiusA = draw.Chance(2) ? Fixed() : Fixed::FromRaw(static_cast<int32_t>(draw.Raw(17) & 0xffff));
    pc.radiusB = draw.Chance(2) ? Fixed() : Fixed::FromRaw(static_cast<int32_t>(draw.Raw(17) & 0xffff));

    // Inverse masses from 2^-12 to 2^23 1/kg (the divisions stay in range), inverse inertias
    // wider still; a static body A has neither.
    b2ContactVelocityConstraint& vc = c.vc;
    vc.indexA = 0;
    vc.indexB = 1;
    vc.contactIndex = 0;
    vc.pointCount = m.pointCount;
    const bool staticA = draw.Chance(5);
    const int mass = draw.Pick(20, 50), turn = draw.Chance(4) ? draw.Pick(20, 60) : draw.Pick(24, 44);
    const auto positive = [&draw](int width) { return Wide::FromRaw(std::abs(draw.Raw(width)) | (int64_t{1} << 20)); };
    vc.invMassA = staticA ? Wide() : positive(mass);
    vc.invIA = staticA ? Wide() : positive(turn);
    vc.invMassB = positive(mass);
    vc.invIB = draw.Chance(10) ? Wide() : positive(turn);
    vc.friction = draw.FixedOf(17);
    vc.restitution = draw.Chance(2) ? Fixed() : draw.Chance(4) ? draw.FixedOf(draw.Pick(1, 31)) : draw.FixedOf(17);
}

// The world points and normal of a case, as the set-up forms them.
b2WorldManifold WorldPoints(const SetUpCase& c) {
    b2Transform xfA, xfB;
    xfA.q = b2Rot(c.poses[0].a);
    xfB.q = b2Rot(c.poses[1].a);
    xfA.p = solver::BodyOrigin(c.poses[0].c, xfA.q, c.pc.localCenterA);
    xfB.p = solver::BodyOrigin(c.poses[1].c, xfB.q, c.pc.localCenterB);
    b2WorldManifold world;
    world.Initialize(&c.manifold, xfA, c.pc.radiusA, xfB, c.pc.radiusB);
    return world;
}

// Velocities of width at most `width` (a static body A keeps its own: the set-up reads it all the same).
void SetUpVelocities(RowDrawer& draw, SetUpCase& c, int width) {
    for (b2Velocity& b : c.velocities) {
        b.v = b2WideVec2(draw.WideOf(width - draw.Pick(0, 1)), draw.WideOf(width - draw.Pick(0, 1)));
        b.w = draw.WideOf(width - draw.Pick(0, 1));
    }
}

struct SetUpDone {
    b2ContactVelocityConstraint vc;
    b2WideSym22 K;  ///< of the templated part alone
    uint64_t saturations = 0;
};

// The solver's whole set-up of the case's contact, with the unchecked set-up allowed or not.
SetUpDone InitializeOnce(b2Contact* contact, const SetUpCase& c, bool unchecked) {
    solver::AllowUncheckedRows(unchecked);
    *contact->GetManifold() = c.manifold;
    b2Position poses[2] = {c.poses[0], c.poses[1]};
    b2Velocity velocities[2] = {c.velocities[0], c.velocities[1]};
    b2CachedRot rotations[2];
    b2ContactPositionConstraint pc = c.pc;
    SetUpDone out;
    out.vc = c.vc;
    b2ContactSolverDef def;
    def.count = 1;
    def.contacts = &contact;
    def.positions = poses;
    def.velocities = velocities;
    def.positionConstraints = &pc;
    def.velocityConstraints = &out.vc;
    def.rotations = rotations;
    b2ContactSolver solver(&def);
    const SaturationCapture capture(&out.saturations);
    solver.InitializeVelocityConstraints(0, 1);
    return out;
}

// Only the templated part (ContactPointSetUp.h), on the number types F, N and V: what the bound
// speaks for.
template <class F, class N, class V>
SetUpDone SetUpPointsOnce(const SetUpCase& c, const b2WorldManifold& world) {
    SetUpDone out;
    out.vc = c.vc;
    out.vc.normal = world.normal;
    out.vc.tangent = b2Cross(world.normal, Fixed(1));
    const b2Velocity& A = c.velocities[0];
    const b2Velocity& B = c.velocities[1];
    const SaturationCapture capture(&out.saturations);
    out.K = solver::SetUpContactPoints<F, N>(out.vc, world.points, c.poses[0].c, c.poses[1].c, V{N(A.v.x), N(A.v.y)},
                                             N(A.w), V{N(B.v.x), N(B.v.y)}, N(B.w));
    return out;
}

// Every field the set-up writes, and the saturations.
bool SameSetUp(const SetUpDone& a, const SetUpDone& b, int32 pointCount) {
    const b2ContactVelocityConstraint &x = a.vc, &y = b.vc;
    if (a.saturations != b.saturations || x.normal != y.normal || x.tangent != y.tangent || x.pushA.x != y.pushA.x ||
        x.pushA.y != y.pushA.y || x.pushB.x != y.pushB.x || x.pushB.y != y.pushB.y || x.samePush != y.samePush ||
        x.pointCount != y.pointCount || x.useBlock != y.useBlock || x.unchecked.velocities != y.unchecked.velocities ||
        x.unchecked.impulses != y.unchecked.impulses || a.K.k11 != b.K.k11 || a.K.k12 != b.K.k12 || a.K.k22 != b.K.k22)
        return false;
    if (x.useBlock &&
        (x.K.k11 != y.K.k11 || x.K.k12 != y.K.k12 || x.K.k22 != y.K.k22 || x.normalMass.k11 != y.normalMass.k11 ||
         x.normalMass.k12 != y.normalMass.k12 || x.normalMass.k22 != y.normalMass.k22))
        return false;
    for (int32 j = 0; j < pointCount; ++j) {
        const b2VelocityConstraintPoint &p = x.points[j], &q = y.points[j];
        if (p.rnA != q.rnA || p.rnB != q.rnB || p.rtA != q.rtA || p.rtB != q.rtB || p.normalMass != q.normalMass ||
            p.tangentMass != q.tangentMass || p.turnNA != q.turnNA || p.turnNB != q.turnNB || p.turnTA != q.turnTA ||
            p.turnTB != q.turnTB || p.velocityBias != q.velocityBias)
            return false;
    }
    return true;
}

TEST(UncheckedRows, ContactSetUpsWithinTheBoundGiveTheTestedSetUpsBits) {
#ifndef LOCKBOX_UNCHECKED_ROWS
    GTEST_SKIP() << "no native 128-bit integer: every set-up keeps its tests";
#else
    // A contact whose manifold each trial overwrites: the set-up reads nothing else of it.
    b2World world(b2Vec2(0, -10));
    test::MakeDynamicBox(world, 0, 0, 1, 1);
    test::MakeDynamicBox(world, 0, Fixed(1.5), 1, 1);
    world.Step(test::kDt, 8, 3);
    b2Contact* contact = world.GetContactList();
    ASSERT_NE(contact, nullptr);

    int64_t bounded = 0, unchecked = 0;
    RunTrials(20261201, "contact set-ups", [&](RowDrawer& draw, Tally& tally) {
        SetUpCase c;
        FillSetUp(draw, c);
        const b2WorldManifold points = WorldPoints(c);
        b2ContactVelocityConstraint bound = c.vc;
        bound.normal = points.normal;
        bound.tangent = b2Cross(points.normal, Fixed(1));
        const int width = solver::SetUpVelocityWidth(bound, points.points, c.poses[0].c, c.poses[1].c);
        const int loosen = Loosening(draw);
        const int loosened = width == 0 ? 0 : std::min(width + loosen, 63);
        if (width != 0) ++bounded;
        SetUpVelocities(draw, c, width == 0 ? draw.Pick(16, 48) : loosened + draw.Pick(-3, 1));
        const bool fits = solver::Within(
            solver::FoldedPair(c.velocities[0].v, c.velocities[0].w, c.velocities[1].v, c.velocities[1].w), loosened);

        using solver::UncheckedFixed, solver::UncheckedVec2, solver::UncheckedWide;
        const SetUpDone tested = SetUpPointsOnce<Fixed, Wide, b2WideVec2>(c, points);
        const SetUpDone fast = SetUpPointsOnce<UncheckedFixed, UncheckedWide, UncheckedVec2>(c, points);
        if (loosen != 0) return tally.Judge(loosen, fits, fits && SameSetUp(fast, tested, c.vc.pointCount), 0);
        // The solver's own choice: the whole set-up, unchecked where it may be, against the tested one.
        const SetUpDone solverFast = InitializeOnce(contact, c, true);
        const SetUpDone solverTested = InitializeOnce(contact, c, false);
        if (fits) ++unchecked;
        const bool same =
            SameSetUp(solverFast, solverTested, c.vc.pointCount) && (!fits || SameSetUp(fast, tested, c.vc.pointCount));
        return tally.Judge(0, fits, same, tested.saturations);
    });
    // Half the set-ups have a bound (the rest are drawn beyond it), and many run unchecked.
    EXPECT_GT(bounded, 25000);
    EXPECT_GT(unchecked, 10000);
#endif
}

// The set-up's bound at its edges: arms, inertias and velocities at the widest it admits, either
// sign, with the restitution at full scale; beyond the arms' edge it admits nothing.
TEST(UncheckedRows, ContactSetUpsAtTheBoundsEdgesGiveTheTestedSetUpsBits) {
#ifndef LOCKBOX_UNCHECKED_ROWS
    GTEST_SKIP() << "no native 128-bit integer: every set-up keeps its tests";
#else
    const QuietTraps quiet;
    int admitted = 0;
    for (int arm = 1; arm <= 29; ++arm) {
        for (int turn = 1; turn <= 63; turn += 2) {
            for (int sign = 0; sign < 16; ++sign) {
                // The widest raws of width `width`, as Within admits them: -(2^width - 1) and
                // 2^width - 2 (a fold is one short for a positive raw).
                const auto edge = [sign](int width, int bit) {
                    const auto top = static_cast<int64_t>((uint64_t{1} << width) - 1);
                    return (sign >> bit & 1) != 0 ? -top : top - 1;
                };
                SetUpCase c;
                c.vc.pointCount = 2;
                c.vc.indexB = 1;
                c.vc.normal = b2Vec2(Fixed::FromRaw(sign & 1 ? -65536 : 65536), Fixed());
                if (sign & 2) c.vc.normal = c.vc.normal.Skew();
                c.vc.tangent = b2Cross(c.vc.normal, Fixed(1));
                c.vc.invMassA = c.vc.invMassB = Wide::FromRaw((int64_t{1} << 45) - 2);
                c.vc.invIA = c.vc.invIB = Wide::FromRaw(edge(turn, 31));
                c.vc.restitution = Fixed(1);
                b2WorldManifold points;
                points.normal = c.vc.normal;
                // Arms of width `arm` from both centres: A at the origin, B across it.
                const auto raw = [](int64_t v) { return Fixed::FromRaw(static_cast<int32_t>(v)); };
                const int64_t half = edge(arm, 0) / 2;
                c.poses[0].c = b2Vec2(raw(half), raw(half));
                c.poses[1].c = b2Vec2(raw(-half), raw(-half));
                points.points[0] = b2Vec2(raw(half - edge(arm - 1, 1)), raw(-half));
                points.points[1] = b2Vec2(raw(half), raw(half + edge(arm - 1, 2)));
                const int width = solver::SetUpVelocityWidth(c.vc, points.points, c.poses[0].c, c.poses[1].c);
                if (width == 0) continue;
                for (b2Velocity& b : c.velocities) {
                    b.v = b2WideVec2(Wide::FromRaw(edge(width, 0)), Wide::FromRaw(-edge(width, 1)));
                    b.w = Wide::FromRaw(edge(width, 2));
                }
                c.velocities[0].v.x = Wide::FromRaw(-c.velocities[1].v.x.Raw());
                c.velocities[0].w = Wide::FromRaw(-c.velocities[1].w.Raw());
                using solver::UncheckedFixed, solver::UncheckedVec2, solver::UncheckedWide;
                const SetUpDone tested = SetUpPointsOnce<Fixed, Wide, b2WideVec2>(c, points);
                const SetUpDone fast = SetUpPointsOnce<UncheckedFixed, UncheckedWide, UncheckedVec2>(c, points);
                ASSERT_EQ(tested.saturations, 0u) << arm << " " << turn << " " << sign;
                ASSERT_TRUE(SameSetUp(fast, tested, 2)) << arm << " " << turn << " " << sign;
                ++admitted;
            }
        }
    }
    EXPECT_GT(admitted, 5000);
#endif
}

// The contact rows' bound in closed form is its step-by-step definition: the same slopes for
// every width of the constants, drawn over their whole ranges and at every corner of them.
TEST(UncheckedRows, ContactRowSlopesInClosedFormAreTheSteps) {
    constexpr solver::RowWidths kWidest{32, 32, 64, solver::kWidestResult, 32};
    const auto same = [](const solver::RowWidths& w, int points) {
        const solver::Slopes closed = solver::RowSlopes(w, points), steps = solver::RowSlopesBySteps(w, points);
        return closed.v == steps.v && closed.i == steps.i;
    };
    const auto describe = [](const solver::RowWidths& w, int points) {
        return ::testing::Message() << points << " points, dir " << w.dir << " arm " << w.arm << " mass " << w.mass
                                    << " resp " << w.resp << " friction " << w.friction;
    };
    std::mt19937_64 rng(20261130);
    const auto up = [&rng](int top) { return std::uniform_int_distribution<int>(0, top)(rng); };
    for (int points = 1; points <= 2; ++points) {
        for (int corner = 0; corner < 32; ++corner) {
            const auto pick = [corner](int bit, int top) { return (corner >> bit) & 1 ? top : 0; };
            const solver::RowWidths w{pick(0, kWidest.dir), pick(1, kWidest.arm), pick(2, kWidest.mass),
                                      pick(3, kWidest.resp), pick(4, kWidest.friction)};
            ASSERT_TRUE(same(w, points)) << describe(w, points);
        }
        for (int i = 0; i < 400000; ++i) {
            const solver::RowWidths w{up(kWidest.dir), up(kWidest.arm), up(kWidest.mass), up(kWidest.resp),
                                      up(kWidest.friction)};
            ASSERT_TRUE(same(w, points)) << describe(w, points);
        }
    }
}

// Point rows of a revolute joint: arms of any length, a point block around 2^mass kg and
// responses around its inverse.
void FillPointRow(RowDrawer& draw, JointSolver::Row& row) {
    row = JointSolver::Row();
    row.indexA = 0;
    row.indexB = 1;
    const int mass = 32 + draw.Pick(-14, 14);
    const int resp = 64 - mass + draw.Pick(-3, 9);
    const int arm = draw.Chance(3) ? draw.Pick(1, 31) : draw.Pick(12, 19);
    row.rA = b2Vec2(draw.FixedOf(arm), draw.FixedOf(arm));
    row.rB = b2Vec2(draw.FixedOf(arm), draw.FixedOf(arm));
    const bool staticA = draw.Chance(5);
    row.mA = staticA ? Wide() : draw.WideOf(resp);
    row.iA = staticA ? Wide() : draw.WideOf(resp);
    row.mB = draw.WideOf(resp);
    row.iB = draw.WideOf(resp);
    row.pointMass =
        b2WideMat22{b2WideVec2(draw.WideOf(mass), draw.WideOf(mass)), b2WideVec2(draw.WideOf(mass), draw.WideOf(mass))};
}

struct PointSolved {
    std::vector<b2Velocity> bodies;
    b2WideVec2 impulse;
    uint64_t saturations = 0;
    bool operator==(const PointSolved& o) const {
        for (size_t i = 0; i < bodies.size(); ++i) {
            if (bodies[i].v.x != o.bodies[i].v.x || bodies[i].v.y != o.bodies[i].v.y || bodies[i].w != o.bodies[i].w)
                return false;
        }
        return impulse.x == o.impulse.x && impulse.y == o.impulse.y && saturations == o.saturations;
    }
};

// What `run` does to a point row and its bodies.
template <class Run>
PointSolved RunPoint(JointSolver::Row row, std::vector<b2Velocity> bodies, Run run) {
    b2SolverData data;
    data.velocities = bodies.data();
    PointSolved out;
    {
        const SaturationCapture capture(&out.saturations);
        run(row, data);
    }
    out.bodies = std::move(bodies);
    out.impulse = row.impulse;
    return out;
}

// One iteration of a point row.
PointSolved SolvePoint(JointSolver::Row row, std::vector<b2Velocity> bodies, bool unchecked) {
    return RunPoint(row, std::move(bodies), [unchecked](JointSolver::Row& r, const b2SolverData& data) {
        JointSolver::SolvePointRow(r, data, unchecked);
    });
}

// The warm start of a point row: its accumulated impulse applied to its bodies.
PointSolved WarmStartPoint(JointSolver::Row row, std::vector<b2Velocity> bodies, bool unchecked) {
    return RunPoint(row, std::move(bodies), [unchecked](JointSolver::Row& r, const b2SolverData& data) {
        JointSolver::WarmStartPointRow(r, data, unchecked);
    });
}

// Trials of point rows through `run` (an iteration or the warm start), both of which the row's
// widths bound.
void PointRowTrials(uint64_t seed, const char* rows,
                    PointSolved (*run)(JointSolver::Row, std::vector<b2Velocity>, bool)) {
    RunTrials(seed, rows, [run](RowDrawer& draw, Tally& tally) {
        JointSolver::Row row;
        FillPointRow(draw, row);
        const solver::InputWidths widths = JointSolver::PointRowWidths(row);
        const int loosen = Loosening(draw);
        row.unchecked = {Loosened(widths.velocities, loosen), Loosened(widths.impulses, loosen)};
        const bool none = widths.velocities == 0 || widths.impulses == 0;
        const int velocityWidth = none ? draw.Pick(16, 48) : row.unchecked.velocities + draw.Pick(-3, 1);
        const int impulseWidth = none ? draw.Pick(16, 48) : row.unchecked.impulses + draw.Pick(-3, 1);
        std::vector<b2Velocity> bodies(2);
        for (b2Velocity& b : bodies) {
            b.v =
                b2WideVec2(draw.WideOf(velocityWidth - draw.Pick(0, 1)), draw.WideOf(velocityWidth - draw.Pick(0, 1)));
            b.w = draw.WideOf(velocityWidth - draw.Pick(0, 1));
        }
        if (row.mA == Wide()) bodies[0] = b2Velocity();
        row.impulse = b2WideVec2(draw.WideOf(impulseWidth), draw.WideOf(impulseWidth));

        const uint64_t velocities = solver::FoldedPair(bodies[0].v, bodies[0].w, bodies[1].v, bodies[1].w);
        const bool fits =
            solver::Within(velocities, row.unchecked.velocities) &&
            solver::Within(solver::Folded(row.impulse.x) | solver::Folded(row.impulse.y), row.unchecked.impulses);
        const PointSolved fast = run(row, bodies, true);
        const PointSolved reference = run(row, bodies, false);
        return tally.Judge(loosen, fits, fast == reference, reference.saturations);
    });
}

TEST(UncheckedRows, PointRowsWithinTheBoundGiveTheTestedRowsBits) {
#ifndef LOCKBOX_UNCHECKED_ROWS
    GTEST_SKIP() << "no native 128-bit integer: every row keeps its tests";
#else
    PointRowTrials(1130, "point rows", SolvePoint);
#endif
}

TEST(UncheckedRows, PointRowWarmStartsWithinTheBoundGiveTheTestedBits) {
#ifndef LOCKBOX_UNCHECKED_ROWS
    GTEST_SKIP() << "no native 128-bit integer: every row keeps its tests";
#else
    PointRowTrials(3011, "point row warm starts", WarmStartPoint);
#endif
}

// Position rows of a revolute joint: anchors and centres of any size, masses and inertias of
// every scale (a row's K is formed from them, so its correction impulse is whatever they give).
void FillPositionRow(RowDrawer& draw, JointSolver::PositionRow& row) {
    row = JointSolver::PositionRow();
    row.indexA = 0;
    row.indexB = 1;
    const int arm = draw.Chance(3) ? draw.Pick(1, 31) : draw.Pick(12, 19);
    row.localAnchorA = b2Vec2(draw.FixedOf(arm), draw.FixedOf(arm));
    row.localCenterA = b2Vec2(draw.FixedOf(arm - draw.Pick(0, 8)), draw.FixedOf(arm - draw.Pick(0, 8)));
    row.localAnchorB = b2Vec2(draw.FixedOf(arm), draw.FixedOf(arm));
    row.localCenterB = b2Vec2(draw.FixedOf(arm - draw.Pick(0, 8)), draw.FixedOf(arm - draw.Pick(0, 8)));
    const int resp = 32 + draw.Pick(-14, 14);
    const bool staticA = draw.Chance(5);
    row.mA = staticA ? Wide() : draw.WideOf(resp + draw.Pick(-4, 4));
    row.iA = staticA ? Wide() : draw.WideOf(resp + draw.Pick(-4, 4));
    row.mB = draw.WideOf(resp + draw.Pick(-4, 4));
    row.iB = draw.WideOf(resp + draw.Pick(-4, 4));
}

// The same centres and angles, to the bit.
bool SamePoses(const std::vector<b2Position>& a, const std::vector<b2Position>& b) {
    for (size_t i = 0; i < a.size(); ++i) {
        if (a[i].c.x != b[i].c.x || a[i].c.y != b[i].c.y || a[i].a != b[i].a) return false;
    }
    return true;
}

struct PositionSolved {
    std::vector<b2Position> bodies;
    bool closed = false;
    uint64_t saturations = 0;
    bool operator==(const PositionSolved& o) const {
        return SamePoses(bodies, o.bodies) && closed == o.closed && saturations == o.saturations;
    }
};

PositionSolved SolvePosition(const JointSolver::PositionRow& row, std::vector<b2Position> bodies, bool unchecked) {
    std::vector<b2CachedRot> rotations(bodies.size());
    b2SolverData data;
    data.positions = bodies.data();
    data.rotations = rotations.data();
    PositionSolved out;
    {
        const SaturationCapture capture(&out.saturations);
        out.closed = JointSolver::SolvePointPositionRow(row, data, unchecked);
    }
    out.bodies = std::move(bodies);
    return out;
}

// The correction impulse of a position row, as the joint computes it.
b2WideVec2 RowImpulse(const JointSolver::PositionRow& row, const std::vector<b2Position>& bodies) {
    const b2Vec2 rA = b2Mul(b2Rot(bodies[0].a), row.localAnchorA - row.localCenterA);
    const b2Vec2 rB = b2Mul(b2Rot(bodies[1].a), row.localAnchorB - row.localCenterB);
    const b2Vec2 C = bodies[1].c + rB - bodies[0].c - rA;
    return jointmath::PointGapImpulse(C, rA, rB, row.mA, row.mB, row.iA, row.iB);
}

TEST(UncheckedRows, PositionRowsWithinTheBoundGiveTheTestedRowsBits) {
#ifndef LOCKBOX_UNCHECKED_ROWS
    GTEST_SKIP() << "no native 128-bit integer: every row keeps its tests";
#else
    RunTrials(2611, "position rows", [](RowDrawer& draw, Tally& tally) {
        JointSolver::PositionRow row;
        FillPositionRow(draw, row);
        const JointSolver::PositionWidths widths = JointSolver::PositionRowWidths(row);
        const int loosen = Loosening(draw);
        // Loosen the poses, the impulses or both.
        const int which = draw.Pick(0, 2);
        row.unchecked = {Loosened(widths.poses, which != 1 ? loosen : 0),
                         Loosened(widths.impulses, which != 0 ? loosen : 0)};
        const int poseWidth = (widths.poses == 0 ? JointSolver::kPoseWidth : row.unchecked.poses) + draw.Pick(-4, 1);
        std::vector<b2Position> bodies(2);
        for (b2Position& b : bodies) {
            b.c = b2Vec2(draw.FixedOf(poseWidth - draw.Pick(0, 1)), draw.FixedOf(poseWidth - draw.Pick(0, 1)));
            b.a = draw.Chance(3) ? draw.FixedOf(draw.Pick(0, 3)) : draw.FixedOf(poseWidth - draw.Pick(0, 1));
        }

        const PositionSolved fast = SolvePosition(row, bodies, true);
        const PositionSolved reference = SolvePosition(row, bodies, false);
        // The row ran wholly unchecked when the poses and its impulse fit. A solve that saturates
        // reports on both paths alike (it is always Wide's); only such a row may saturate.
        using solver::Folded;
        const uint64_t poses = solver::FoldedPair(bodies[0].c, bodies[0].a, bodies[1].c, bodies[1].a);
        const b2WideVec2 impulse = RowImpulse(row, bodies);
        const bool fits = solver::Within(poses, row.unchecked.poses) &&
                          solver::Within(Folded(impulse.x) | Folded(impulse.y), row.unchecked.impulses);
        const bool solveSaturated = impulse.x.Raw() == Wide::kMaxRaw || impulse.x.Raw() == -Wide::kMaxRaw ||
                                    impulse.y.Raw() == Wide::kMaxRaw || impulse.y.Raw() == -Wide::kMaxRaw;
        return tally.Judge(loosen, fits, fast == reference, solveSaturated ? 0 : reference.saturations);
    });
#endif
}

// A face manifold's position constraint: local points, centres and normals of every size, radii,
// masses and inertias of every scale (now and then beyond the bound: a normal that is not unit,
// points or radii too wide), a static body A now and then.
void FillFacePosition(RowDrawer& draw, b2ContactPositionConstraint& pc) {
    pc = b2ContactPositionConstraint();
    pc.indexA = 0;
    pc.indexB = 1;
    pc.type = draw.Chance(2) ? b2Manifold::e_faceA : b2Manifold::e_faceB;
    pc.pointCount = draw.Pick(1, 2);
    pc.localNormal = draw.Direction(10);
    const int local = draw.Chance(4) ? draw.Pick(1, 30) : draw.Pick(12, 22);
    pc.localPoint = b2Vec2(draw.FixedOf(local), draw.FixedOf(local));
    for (int32 j = 0; j < pc.pointCount; ++j)
        pc.localPoints[j] = b2Vec2(draw.FixedOf(local - draw.Pick(0, 2)), draw.FixedOf(local - draw.Pick(0, 2)));
    pc.localCenterA = draw.Chance(2) ? b2Vec2() : b2Vec2(draw.FixedOf(local - 2), draw.FixedOf(local - 2));
    pc.localCenterB = draw.Chance(2) ? b2Vec2() : b2Vec2(draw.FixedOf(local - 2), draw.FixedOf(local - 2));
    const int radius = draw.Chance(8) ? draw.Pick(1, 31) : draw.Pick(0, 12);
    pc.radiusA = Fixed::FromRaw(static_cast<int32_t>(std::abs(draw.Raw(radius))));
    pc.radiusB = Fixed::FromRaw(static_cast<int32_t>(std::abs(draw.Raw(radius))));
    const bool staticA = draw.Chance(5);
    const int mass = draw.Pick(16, 56), turn = draw.Chance(4) ? draw.Pick(16, 62) : draw.Pick(24, 48);
    const auto positive = [&draw](int width) { return Wide::FromRaw(std::abs(draw.Raw(width))); };
    pc.invMassA = staticA ? Wide() : positive(mass - draw.Pick(0, 4));
    pc.invIA = staticA ? Wide() : positive(turn - draw.Pick(0, 4));
    pc.invMassB = draw.Chance(4) ? pc.invMassA : positive(mass - draw.Pick(0, 4));
    pc.invIB = positive(turn - draw.Pick(0, 4));
}

// One pass of the solver over the constraint: the discrete pass, or now and then the
// time-of-impact pass with A held still or not.
struct FacePass {
    bool toi = false;
    int32 toiIndexA = 0;
};

struct FaceSolved {
    std::vector<b2Position> bodies;
    Fixed minSeparation;
    bool toiDone = false;
    uint64_t saturations = 0;
    bool operator==(const FaceSolved& o) const {
        return SamePoses(bodies, o.bodies) && minSeparation == o.minSeparation && toiDone == o.toiDone &&
               saturations == o.saturations;
    }
};

FaceSolved SolveFaces(b2ContactPositionConstraint pc, std::vector<b2Position> bodies, FacePass pass, bool unchecked) {
    solver::AllowUncheckedRows(unchecked);
    std::vector<b2CachedRot> rotations(bodies.size());
    b2ContactSolverDef def;
    def.count = 1;
    def.positions = bodies.data();
    def.positionConstraints = &pc;
    def.rotations = rotations.data();
    b2ContactSolver solver(&def);
    FaceSolved out;
    {
        const SaturationCapture capture(&out.saturations);
        if (pass.toi)
            out.toiDone = solver.SolveTOIPositionConstraints(pass.toiIndexA, 1);
        else
            out.minSeparation = solver.SolvePositionConstraints(0, 1);
    }
    out.bodies = std::move(bodies);
    return out;
}

// Whether every point of the pass is within the constraint's widths (the poses, then the located
// point, then its impulse), followed on the tested path.
bool FacesFit(const b2ContactPositionConstraint& pc, std::vector<b2Position> bodies, FacePass pass) {
    solver::PairMasses<Wide> masses{pc.invMassA, pc.invMassB, pc.invIA, pc.invIB};
    if (pass.toi && pass.toiIndexA != 0) masses.mA = masses.iA = Wide();
    b2Vec2 cA = bodies[0].c, cB = bodies[1].c;
    Fixed aA = bodies[0].a, aB = bodies[1].a;
    for (int32 j = 0; j < pc.pointCount; ++j) {
        if (!solver::Within(solver::FoldedPair(cA, aA, cB, aB), pc.unchecked.poses)) return false;
        b2Transform xfA, xfB;
        xfA.q = b2Rot(aA);
        xfB.q = b2Rot(aB);
        xfA.p = solver::BodyOrigin(cA, xfA.q, pc.localCenterA);
        xfB.p = solver::BodyOrigin(cB, xfB.q, pc.localCenterB);
        const solver::PositionPoint p = solver::LocateFacePoint<Fixed>(pc, xfA, xfB, cA, cB, j);
        if (!solver::FacePointFits(pc, p)) return false;
        const solver::PositionCorrection c =
            solver::CorrectPoint<Fixed, Wide>(p, masses, pass.toi ? b2_toiBaugarte : b2_baumgarte);
        if (c.impulse != Wide() && !solver::Within(solver::Folded(c.impulse), pc.unchecked.impulses)) return false;
        solver::ApplyCorrection<Fixed, Wide>(p.normal, c, masses, cA, aA, cB, aB);
    }
    return true;
}

TEST(UncheckedRows, FacePositionsWithinTheBoundGiveTheTestedBits) {
#ifndef LOCKBOX_UNCHECKED_ROWS
    GTEST_SKIP() << "no native 128-bit integer: every row keeps its tests";
#else
    RunTrials(2612, "face positions", [](RowDrawer& draw, Tally& tally) {
        b2ContactPositionConstraint pc;
        FillFacePosition(draw, pc);
        const b2ContactPositionConstraint::Widths widths = solver::FacePositionWidths(pc);
        const int loosen = Loosening(draw);
        // Loosen the poses, the reference arm, the impulses or all.
        const int which = draw.Pick(0, 3);
        const auto loose = [&](uint8_t width, int kind) {
            return Loosened(width, which == kind || which == 3 ? loosen : 0);
        };
        pc.unchecked = {loose(widths.poses, 0), loose(widths.arm, 1), loose(widths.impulses, 2)};
        // A's centre near the pose bound's edge, B's at an offset near the arm's edge.
        const bool bounded = widths.poses != 0;
        const int poseWidth = (bounded ? pc.unchecked.poses : solver::kPoseWidth) + draw.Pick(-6, 1);
        const int reach = bounded ? pc.unchecked.arm : 24;
        const int offset = draw.Chance(4) ? draw.Pick(1, 31) : reach + draw.Pick(-4, 1);
        std::vector<b2Position> bodies(2);
        bodies[0].c = b2Vec2(draw.FixedOf(poseWidth - draw.Pick(0, 1)), draw.FixedOf(poseWidth - draw.Pick(0, 1)));
        const auto near = [&](Fixed c) {
            return Fixed::FromRaw(static_cast<int32_t>(std::clamp<int64_t>(
                int64_t{c.Raw()} + draw.Raw(offset - draw.Pick(0, 1)), -Fixed::kMaxRaw, Fixed::kMaxRaw)));
        };
        bodies[1].c = b2Vec2(near(bodies[0].c.x), near(bodies[0].c.y));
        for (b2Position& b : bodies)
            b.a = draw.Chance(3) ? draw.FixedOf(draw.Pick(0, 19)) : draw.FixedOf(poseWidth - draw.Pick(0, 1));
        FacePass pass;
        if (draw.Chance(4)) pass = {true, draw.Chance(2) ? 0 : 2};

        const FaceSolved fast = SolveFaces(pc, bodies, pass, true);
        const FaceSolved reference = SolveFaces(pc, bodies, pass, false);
        const bool fits = FacesFit(pc, bodies, pass);
        return tally.Judge(loosen, fits, fast == reference, reference.saturations);
    });
#endif
}

// The rotations the rows take have |c|, |s| <= 1 (raw 2^16), as their bound assumes: every
// angle of four turns either way, and angles out to the end of the Q16.16 range.
TEST(UncheckedRows, RotationsStayWithinOne) {
    const auto within = [](int32_t raw) {
        b2Rot q;
        q.Set(Fixed::FromRaw(raw));
        return std::abs(q.c.Raw()) <= 65536 && std::abs(q.s.Raw()) <= 65536;
    };
    constexpr int32_t kFourTurns = 1647099;  // 8 pi in raw units, rounded up
    for (int32_t raw = -kFourTurns; raw <= kFourTurns; ++raw) ASSERT_TRUE(within(raw)) << raw;
    std::mt19937 rng(26);
    for (int i = 0; i < 1000000; ++i) ASSERT_TRUE(within(static_cast<int32_t>(rng()))) << i;
    ASSERT_TRUE(within(INT32_MAX));
    ASSERT_TRUE(within(INT32_MIN));
    ASSERT_TRUE(within(-INT32_MAX));
}

// The hashes of a pyramid dropped from a height beside a chain swinging from a pin: while the
// pyramid lands, some rows are beyond their bound and keep their tests.
std::vector<uint64_t> Hashes(bool unchecked) {
    solver::AllowUncheckedRows(unchecked);
    b2World world(b2Vec2(0, -10));
    test::MakeBoxPyramid(world, 12, 150, 101);
    b2BodyDef pinDef;
    pinDef.position.Set(-20, 30);
    b2Body* previous = world.CreateBody(&pinDef);
    b2PolygonShape link;
    link.SetAsBox(Fixed(0.5), Fixed(0.125));
    for (int i = 0; i < 20; ++i) {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position.Set(Fixed(-19.5) + Fixed(i), 30);
        b2Body* body = world.CreateBody(&def);
        body->CreateFixture(&link, 1);
        b2RevoluteJointDef joint;
        joint.Initialize(previous, body, b2Vec2(Fixed(-20) + Fixed(i), 30));
        world.CreateJoint(&joint);
        previous = body;
    }
    return test::StepHashes(world, 120);
}

TEST(UncheckedRows, WorldsGiveTheSameHashesWithAndWithoutUncheckedRows) {
    const UncheckedAllowed restore;
    EXPECT_EQ(Hashes(true), Hashes(false));
}

// Revolute joints of every kind a row's set-up meets: bodies of masses from grams to tonnes,
// fixed rotation, static bodies, anchors near and beyond the rows' bounds, limits and motors (the
// limits switched off midway, which turns those joints into rows), warm starting on or off, and a
// time step that changes. The set-up that writes straight into the rows must give the joint's own bits.
struct RevoluteRun {
    std::vector<uint64_t> hashes;
    uint64_t saturations = 0;
    bool operator==(const RevoluteRun&) const = default;
};

RevoluteRun RevoluteWorld(uint64_t seed, bool unchecked) {
    solver::AllowUncheckedRows(unchecked);
    std::mt19937_64 rng(seed);
    const auto pick = [&rng](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    const auto raw = [](int32_t r) { return Fixed::FromRaw(r); };
    RevoluteRun run;
    const SaturationCapture capture(&run.saturations);
    b2World world(b2Vec2(0, -10));
    world.SetWarmStarting(pick(0, 3) != 0);
    std::vector<b2Body*> bodies;
    for (int i = 0; i < 24; ++i) {
        b2BodyDef def;
        def.type = i > 0 && pick(0, 5) == 0 ? b2_staticBody : b2_dynamicBody;
        const int reach = pick(0, 7) == 0 ? 9000 : 30;
        def.position.Set(Fixed(pick(-reach, reach)), Fixed(pick(-reach, reach)));
        def.angle = raw(pick(-400000, 400000));
        def.fixedRotation = pick(0, 9) == 0;
        def.linearVelocity.Set(Fixed(pick(-6, 6)), Fixed(pick(-6, 6)));
        def.angularVelocity = Fixed(pick(-4, 4));
        b2Body* body = world.CreateBody(&def);
        b2CircleShape circle;
        circle.m_radius = raw(pick(2000, 300000));
        body->CreateFixture(&circle, raw(pick(60, 6553600)));  // 0.001 to 100 kg/m^2
        bodies.push_back(body);
    }
    std::vector<b2RevoluteJoint*> joints;
    for (int i = 1; i < 24; ++i) {
        b2RevoluteJointDef def;
        def.bodyA = bodies[static_cast<size_t>(pick(0, i - 1))];
        def.bodyB = bodies[static_cast<size_t>(i)];
        const int reach = pick(0, 6) == 0 ? 196608000 : 196608;  // 3000 m or 3 m, raw
        def.localAnchorA.Set(raw(pick(-reach, reach)), raw(pick(-reach, reach)));
        def.localAnchorB.Set(raw(pick(-reach, reach)), raw(pick(-reach, reach)));
        def.enableLimit = pick(0, 5) == 0;
        def.lowerAngle = raw(pick(-100000, 0));
        def.upperAngle = raw(pick(0, 100000));
        def.enableMotor = pick(0, 5) == 0;
        def.motorSpeed = Fixed(pick(-3, 3));
        def.maxMotorTorque = Fixed(pick(1, 50));
        joints.push_back(static_cast<b2RevoluteJoint*>(world.CreateJoint(&def)));
    }
    for (int step = 0; step < 60; ++step) {
        if (step == 25) {
            for (b2RevoluteJoint* joint : joints) joint->EnableLimit(false);
        }
        const Fixed dt = step % 17 == 5 ? raw(728) : test::kDt;
        world.Step(dt, 8, 3);
        run.hashes.push_back(world.Hash());
    }
    return run;
}

TEST(UncheckedRows, RevoluteSetUpsGiveTheJointsOwnBits) {
    const QuietTraps quiet;
    const UncheckedAllowed restore;
    for (uint64_t seed = 1; seed <= 24; ++seed) {
        const RevoluteRun reference = RevoluteWorld(seed, false);
        EXPECT_EQ(RevoluteWorld(seed, true), reference) << "seed " << seed;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
