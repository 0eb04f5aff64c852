// Cases 1-5: stacks and piles at the edges of the Q16.16/Q32.32 envelope (NUMERICS Table 1 and
// stability tests 8): tall stack, pyramids, tiny bodies, large bodies, mass ratios.
//
// Units: lengths m, speeds m/s, steps of 1/60 s. Every limit below is written with the figure
// measured when it was set (docs/stability.md) and the margin chosen.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "Harness.h"

namespace lockbox::stability::detail {
namespace {

/// Observations of a settling run.
struct Settle {
    int sleepStep = -1;   ///< first step count after which every dynamic body sleeps (-1: never)
    double maxPen = 0;    ///< largest penetration from settleFrom on, m
    double maxDrift = 0;  ///< largest |x - x0| of the tracked body, m
    double maxSpeed = 0;  ///< largest body speed over the run, m/s
    double finalSag = 0;  ///< restY - final y of the tracked body, m
};

/// Steps until everything sleeps (or maxSteps), tracking `top` against (x0, restY).
Settle RunSettle(Sim& sim, b2Body* top, double restY, int maxSteps, int settleFrom) {
    Settle s;
    const double x0 = D(top->GetPosition().x);
    for (int i = 0; i < maxSteps; ++i) {
        sim.Step();
        if (i + 1 >= settleFrom) s.maxPen = std::max(s.maxPen, MaxPenetration(sim.world()));
        s.maxDrift = std::max(s.maxDrift, std::fabs(D(top->GetPosition().x) - x0));
        s.maxSpeed = std::max(s.maxSpeed, MaxSpeed(sim.world()));
        if (AllAsleep(sim.world())) {
            s.sleepStep = i + 1;
            break;
        }
    }
    s.finalSag = restY - D(top->GetPosition().y);
    return s;
}

/// Sleep step as a judged figure: "never" counts as maxSteps + 1, which fails a limit < that.
double SleepFigure(const Settle& s, int maxSteps) { return s.sleepStep < 0 ? maxSteps + 1 : s.sleepStep; }

/// 2 * b2_linearSlop = 0.01 m: the suite's resting-penetration bound (a stack settles at about
/// one slop, since position correction stops at linearSlop).
constexpr double kTwoSlop = 2 * 328.0 / 65536.0;

}  // namespace

// 1. Twenty 0.5 m boxes, each dropped from 0.02 m above the one below (the skin is 0.01 m).
void TallStack(CaseReport& r, Budget) {
    // Limits: sleeping within 10 s (600 steps; measured 209); the top box must not walk
    // sideways (measured 0.43 mm: every rounding is symmetric, but the two contact points of a
    // face are solved in order, and the asymmetry this leaves is below the Q16.16 quantum,
    // which the Q32.32 solver velocities now keep; before them it rounded away to 0) and must
    // not sink below the ideal top height of 20 stacked boxes, 9.75 m (sag = 9.75 - final y;
    // measured -0.308 m: each contact keeps the two 0.01 m polygon skins less about one slop).
    constexpr int kMaxSteps = 1200;
    constexpr double kSleepLimit = 600;
    constexpr double kDriftLimit = 0.005;
    constexpr double kSagLimit = 0;
    Sim sim(r);
    sim.GroundBox(20, Fixed(0.5), b2Vec2(0, Fixed(-0.5)));
    b2Body* top = nullptr;
    for (int i = 0; i < 20; ++i)
        top = sim.Box(b2Vec2(0, Fixed::FromRatio(25 + 52 * i, 100)), Fixed(0.25), Fixed(0.25), 1);
    const Settle s = RunSettle(sim, top, 9.75, kMaxSteps, 1);
    Check(r, "sleep_step", SleepFigure(s, kMaxSteps), kSleepLimit);
    Check(r, "top_drift_m", s.maxDrift, kDriftLimit);
    Check(r, "top_sag_m", s.finalSag, kSagLimit);
}

namespace {
/// A pyramid of `base` boxes (1 m, density 5, friction 0.2: the fixture default, as the
/// pyramid20 scene) laid out as pyramid20 (SCENES.md), generalised:
/// x = -0.5625 base + 0.5625 i + 1.125 (j - i), y = 0.75 + 1.25 i. Returns the apex.
b2Body* BuildPyramid(Sim& sim, int base) {
    sim.GroundEdge(b2Vec2(-60, 0), b2Vec2(60, 0));
    b2Body* apex = nullptr;
    for (int i = 0; i < base; ++i)
        for (int j = i; j < base; ++j)
            apex = sim.Box(
                b2Vec2(Fixed::FromRatio(-9 * base + 9 * i + 18 * (j - i), 16), Fixed::FromRatio(12 + 20 * i, 16)),
                Fixed(0.5), Fixed(0.5), 5, Fixed(0.2));
    return apex;
}
}  // namespace

// 2. Pyramids with bases 20 and 40 for 1200 steps; penetration judged after 300 steps (5 s).
void Pyramids(CaseReport& r, Budget b) {
    // Limits. Base 20 must not collapse (SCENES.md: the apex moves less than 0.5 m either way;
    // measured 0.03 m). The suite's penetration bound, 2 linearSlop (0.01 m), is beyond
    // 2.2.1's solver at these heights: the bottom rows carry the pyramid with 8 velocity and 3
    // position iterations and sink further. Documented limitations, bounded at the measured
    // figures plus margin:
    // - penetration: base 20 0.0134 m (float Box2D 2.4.1: 0.0133 m), base 40 0.0504 m since
    //   the translation-invariant transform (0.0264 m before; float: 0.0351 m): the slipping
    //   top rows make it chaotic, so its bound has a wide margin;
    // - base 40: the top rows slip while the pyramid settles: the apex ends 0.876 m sideways
    //   and 0.578 m low (float Box2D 2.4.1 on the same layout: 0.207 m sideways, 0.43 m high),
    //   so base 40 misses SCENES.md's no-collapse criterion; bounds 1.2 m and 1.0 m.
    constexpr int kSteps = 1200;
    constexpr int kSettleFrom = 300;
    struct Limits {
        int base;
        double pen, apexDx, apexSag;
        bool apexLimitation;
    };
    const Limits limits[2] = {{20, 0.02, 0.5, 0.5, false}, {40, 0.075, 1.2, 1.0, true}};
    const int count = b == Budget::full ? 2 : 1;  // base 40 (820 bodies) is a heavy test
    for (int k = 0; k < count; ++k) {
        const Limits& l = limits[k];
        Sim sim(r);
        b2Body* apex = BuildPyramid(sim, l.base);
        const double x0 = D(apex->GetPosition().x);
        const double restY = 0.5 + (l.base - 1);  // boxes of 1 m resting on each other
        double maxPen = 0;
        for (int i = 0; i < kSteps; ++i) {
            sim.Step();
            if (i + 1 >= kSettleFrom) maxPen = std::max(maxPen, MaxPenetration(sim.world()));
        }
        const std::string p = "base" + std::to_string(l.base) + "_";
        Check(r, p + "max_pen_m", maxPen, l.pen, true);
        Check(r, p + "apex_abs_dx_m", std::fabs(D(apex->GetPosition().x) - x0), l.apexDx, l.apexLimitation);
        Check(r, p + "apex_sag_m", restY - D(apex->GetPosition().y), l.apexSag, l.apexLimitation);
    }
}

// 3. Tiny bodies: a 10-box stack of 0.1 m boxes at density 0.1 (mass 1e-3 kg, inertia 1.7e-6:
// NUMERICS Table 1's underflow corner), and a pile of 20 circles of 0.1 m.
void TinyBodies(CaseReport& r, Budget) {
    // Limits: both sleep within 10 s (measured: stack 69, pile 109 steps); the stack's top box
    // stays in its column within 5 mm (measured 0.14 mm) and the penetration after 2 s stays
    // within 2 slop (measured 0: the skins keep them apart).
    constexpr int kMaxSteps = 1200;
    constexpr double kSleepLimit = 600;
    {
        Sim sim(r);
        sim.GroundBox(2, Fixed(0.5), b2Vec2(0, Fixed(-0.5)));
        b2Body* top = nullptr;
        for (int i = 0; i < 10; ++i)
            top = sim.Box(b2Vec2(0, Fixed::FromRatio(5 + 12 * i, 100)), Fixed(0.05), Fixed(0.05), Fixed(0.1));
        const Settle s = RunSettle(sim, top, 0.95, kMaxSteps, 120);
        Check(r, "stack_sleep_step", SleepFigure(s, kMaxSteps), kSleepLimit);
        Check(r, "stack_top_drift_m", s.maxDrift, 0.005);
        Check(r, "stack_max_pen_m", s.maxPen, kTwoSlop);
    }
    {
        Sim sim(r);
        // A 1 m wide cup: floor and two walls.
        sim.GroundBox(Fixed(0.6), Fixed(0.05), b2Vec2(0, Fixed(-0.05)));
        sim.GroundBox(Fixed(0.05), 1, b2Vec2(Fixed(-0.55), 1));
        sim.GroundBox(Fixed(0.05), 1, b2Vec2(Fixed(0.55), 1));
        b2Body* first = nullptr;
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 4; ++col) {
                // Staggered by 0.02 m per row so the pile does not stand in perfect columns.
                b2Body* c = sim.Ball(
                    b2Vec2(Fixed::FromRatio(-30 + 20 * col + 2 * row, 100), Fixed::FromRatio(10 + 15 * row, 100)),
                    Fixed(0.05), Fixed(0.1));
                if (!first) first = c;
            }
        const Settle s = RunSettle(sim, first, 0, kMaxSteps, 120);
        Check(r, "pile_sleep_step", SleepFigure(s, kMaxSteps), kSleepLimit);
        Check(r, "pile_max_pen_m", s.maxPen, kTwoSlop);
    }
}

// 4. Large bodies: ten 10 m boxes at density 10 (1000 kg, I = 1.67e4 kg m^2) on a 50 m static
// ground, each dropped from 0.04 m above the one below.
void LargeBodies(CaseReport& r, Budget) {
    // Limits: sleep within 10 s (measured 87), column drift 0.05 m (measured 1.5e-5 m),
    // penetration after 2 s within 2 slop (the slop does not scale with the body; measured 0).
    constexpr int kMaxSteps = 1200;
    Sim sim(r);
    sim.GroundBox(25, Fixed(0.5), b2Vec2(0, Fixed(-0.5)));
    b2Body* top = nullptr;
    for (int i = 0; i < 10; ++i) top = sim.Box(b2Vec2(0, Fixed::FromRatio(504 + 1004 * i, 100)), 5, 5, 10);
    const Settle s = RunSettle(sim, top, 95, kMaxSteps, 120);
    Check(r, "sleep_step", SleepFigure(s, kMaxSteps), 600);
    Check(r, "top_drift_m", s.maxDrift, 0.05);
    Check(r, "max_pen_m", s.maxPen, kTwoSlop);
}

// 5. Mass ratios: a heavy 1 m box resting on a light one (the pair), and a four-box column
// alternating light and heavy (the stack), at 10:1, 100:1 and 1000:1, each box dropped from
// 0.04 m above the one below.
void MassRatios(CaseReport& r, Budget) {
    // 10:1 is the manual's stated limit: it must settle within 2 slop, sleep within 10 s, and
    // nothing may move faster than the initial drops give (bound 2 m/s). 100:1 and 1000:1 are
    // beyond it: their figures are documented limitations (docs/stability.md), bounded at the
    // measured value with a margin so that a regression shows:
    // - 100:1 pair: settles with 0.016-0.024 m penetration, sleeps at step 139-149;
    // - 1000:1 pair: the light box is squeezed out sideways at the speed cap (120 m/s,
    //   b2_maxTranslation per step) after sinking 0.74 m into it, and falls off the ground: it
    //   never sleeps (figure 1801 = "not within 1800 steps").
    // The stacks are judged as ensembles (the median over 64 starts, the top box moved sideways
    // by 0 to 11 mm), because the light boxes are crushed and the column topples or holds by
    // sub-millimetre detail: moving the top box by 0.17 mm took one run's 100:1 sleep step from
    // 737 to 1801 and its 1000:1 kick from 4.8 to 120 m/s, on float Box2D as on lockbox. Medians
    // measured over the same 64 starts (lockbox / float Box2D 2.4.1):
    // - 100:1 stack: crushed to about 0.14 m, kicked at 7.2 m/s (7.2), sleeps at step 1,330
    //   (1,072; before Q32.32 velocities 1,258);
    // - 1000:1 stack: holds at 0.009 m, sleeps at step 209 (151), kicked at 8.0 m/s while
    //   settling (4.7; before Q32.32 velocities 7.3).
    constexpr int kMaxSteps = 1800;
    constexpr int kStarts = 64;
    struct Limits {
        int ratio;
        bool stack;
        double pen, sleep, speed;
        bool limitation;
    };
    const Limits limits[6] = {
        {10, false, kTwoSlop, 600, 2, false},  {10, true, kTwoSlop, 600, 2, false},
        {100, false, 0.025, 300, 1.5, true},   {100, true, 0.2, 1650, 11, true},
        {1000, false, 1.1, 1801, 120.1, true}, {1000, true, 0.015, 300, 11, true},
    };
    for (const Limits& l : limits) {
        const int n = l.stack ? 4 : 2;
        // One start: the top box moved sideways by `shift`.
        auto run = [&](Fixed shift) {
            Sim sim(r);
            sim.GroundBox(10, Fixed(0.5), b2Vec2(0, Fixed(-0.5)));
            b2Body* top = nullptr;
            for (int i = 0; i < n; ++i)
                top = sim.Box(b2Vec2(i == n - 1 ? shift : Fixed(), Fixed::FromRatio(52 + 104 * i, 100)), Fixed(0.5),
                              Fixed(0.5), (i % 2) ? Fixed(l.ratio) : Fixed(1));
            const Settle s = RunSettle(sim, top, 0.5 + (n - 1), kMaxSteps, 120);
            return std::vector<double>{s.maxPen, SleepFigure(s, kMaxSteps), s.maxSpeed};
        };
        const bool ensemble = l.stack && l.ratio > 10;
        const std::vector<double> f = ensemble ? EnsembleMedians(kStarts, run) : run(Fixed());
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "r" + std::string.
        std::string q = "r";
        q += std::to_string(l.ratio);
        q += l.stack ? "_stack_" : "_pair_";
        if (ensemble) q += "median_";
        Check(r, q + "max_pen_m", f[0], l.pen, l.limitation);
        Check(r, q + "sleep_step", f[1], l.sleep, l.limitation);
        Check(r, q + "max_speed_mps", f[2], l.speed, l.limitation);
    }
}

}  // namespace lockbox::stability::detail
