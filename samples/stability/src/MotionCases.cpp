// Cases 6, 7, 8 and 11: fast and violent motion: a wrecking ball, bullets at the speed cap,
// boxes spawned inside each other, and a perfectly elastic pile.
//
// Units: lengths m, speeds m/s, energies J, steps of 1/60 s.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "Harness.h"

namespace lockbox::stability::detail {

namespace {
/// Largest single-joint and summed anchor separations over a 1200-step swing of a ball (radius
/// 1 m, density ballDensity) on 30 links (0.5 m x 2 hy, density linkDensity) pinned at (0, 20)
/// and released horizontally; also the largest body speed.
struct Swing {
    double worstJoint = 0, worstTotal = 0, maxSpeed = 0;
};
Swing RunWreckingBall(CaseReport& r, Fixed linkDensity, Fixed hy, Fixed ballDensity) {
    Sim sim(r);
    b2BodyDef gd;
    b2Body* ground = sim.world().CreateBody(&gd);
    const Fixed y = 20;
    b2Body* prev = ground;
    for (int i = 0; i < 30; ++i) {
        b2Body* link = sim.Box(b2Vec2(Fixed::FromRatio(1 + 2 * i, 4), y), Fixed(0.25), hy, linkDensity, Fixed(0.2));
        b2RevoluteJointDef jd;
        jd.collideConnected = false;
        jd.Initialize(prev, link, b2Vec2(Fixed::FromRatio(i, 2), y));
        sim.world().CreateJoint(&jd);
        prev = link;
    }
    b2Body* ball = sim.Ball(b2Vec2(16, y), 1, ballDensity, Fixed(0.2));
    b2RevoluteJointDef jd;
    jd.Initialize(prev, ball, b2Vec2(15, y));
    sim.world().CreateJoint(&jd);

    Swing s;
    for (int i = 0; i < 1200; ++i) {
        sim.Step();
        double total = 0;
        for (b2Joint* j = sim.world().GetJointList(); j; j = j->GetNext()) {
            const double dx = D(j->GetAnchorA().x) - D(j->GetAnchorB().x);
            const double dy = D(j->GetAnchorA().y) - D(j->GetAnchorB().y);
            const double sep = std::sqrt(dx * dx + dy * dy);
            s.worstJoint = std::max(s.worstJoint, sep);
            total += sep;
        }
        s.worstTotal = std::max(s.worstTotal, total);
        s.maxSpeed = std::max(s.maxSpeed, MaxSpeed(sim.world()));
    }
    return s;
}
}  // namespace

// 6. A wrecking ball on a chain of 30 revolute-jointed links, released horizontally 15 m from
// the pivot, swinging for 1200 steps: a 62.8 kg ball (density 20) on 2.5 kg links (0.5 x
// 0.25 m, density 20), 25:1; and the extreme 157 kg ball on 0.0625 kg links (0.5 x 0.125 m,
// density 1), 2500:1.
void WreckingBall(CaseReport& r, Budget) {
    {
        // Limits: 2.2.1's chain has no rope joint, so the links stretch under the ball at the
        // bottom of the swing. Measured on lockbox: 0.092 m worst joint, 2.32 m summed over the
        // 31 joints (float Box2D 2.4.1: 0.092 m and 2.32 m). Bounds: 0.15 m and 3.5 m; speed
        // below free fall from 16 m (17.9 m/s) plus 2 m/s of chain whip (measured 18.6 m/s).
        const Swing s = RunWreckingBall(r, 20, Fixed(0.125), 20);
        Check(r, "ratio25_max_joint_stretch_m", s.worstJoint, 0.15);
        Check(r, "ratio25_max_total_stretch_m", s.worstTotal, 3.5);
        Check(r, "ratio25_max_speed_mps", s.maxSpeed, 20);
    }
    {
        // Documented limitation: at 2500:1 the chain cannot hold the ball in 8 iterations; the
        // joints tear apart by up to 105 m (float Box2D 2.4.1: 112 m) and the ball falls at the
        // speed cap. The figures are regression bounds on that failure: it stays finite (no
        // speed beyond the 120 m/s cap, no saturation) and tears no further than measured plus
        // margin: 150 m for one joint, 2500 m summed (measured 1754 m; float 1755 m).
        const Swing s = RunWreckingBall(r, 1, Fixed(0.0625), 50);
        Check(r, "ratio2500_max_joint_stretch_m", s.worstJoint, 150, true);
        Check(r, "ratio2500_max_total_stretch_m", s.worstTotal, 2500, true);
        Check(r, "ratio2500_max_speed_mps", s.maxSpeed, 120.1, true);
    }
}

namespace {

/// Remembers whether the bullet began touching any body other than `ignore`.
class HitListener : public b2ContactListener {
public:
    HitListener(b2Body* bullet, b2Body* ignore) : bullet_(bullet), ignore_(ignore) {}
    void BeginContact(b2Contact* c) override {
        b2Body* a = c->GetFixtureA()->GetBody();
        b2Body* b = c->GetFixtureB()->GetBody();
        if (a != bullet_ && b != bullet_) return;
        const b2Body* other = a == bullet_ ? b : a;
        if (other != ignore_) hit = true;
    }
    bool hit = false;

private:
    b2Body* bullet_;
    b2Body* ignore_;
};

/// The bullet: a 0.25 m circle (r 0.125), density 1, flagged as a bullet.
b2Body* MakeBullet(Sim& sim, const b2Vec2& p, const b2Vec2& v) {
    b2Body* b = sim.Ball(p, Fixed(0.125), 1);
    b->SetBullet(true);
    b->SetLinearVelocity(v);
    return b;
}

/// 120 m/s: b2_maxTranslation (2 m) per step at 60 Hz, less the rounding of dt (1.9995 m).
constexpr Fixed kMaxSpeed = 120;
/// 120 / sqrt(2) m/s, rounded: the 45-degree shot at the speed cap.
constexpr Fixed kDiagonal = Fixed::FromRaw(5560914);

}  // namespace

// 7. Bullets at the speed cap against a 0.1 m static wall, a dynamic stack and a chain terrain,
// each from 16 start positions spread over one step of travel (2 m) so every phase of the
// crossing is tried. Limit: no tunnel, ever.
void Bullets(CaseReport& r, Budget) {
    constexpr int kShots = 16;
    int wallTunnels = 0, stackTunnels = 0, terrainTunnels = 0;
    for (int k = 0; k < kShots; ++k) {
        const Fixed phase = Fixed::FromRatio(k, 8);  // 0 .. 1.875 m in 1/8 m steps
        {
            // Static wall 0.1 m thick (x 9.95 .. 10.05), no gravity.
            Sim sim(r, b2Vec2(0, 0));
            sim.GroundBox(Fixed(0.05), 5, b2Vec2(10, 0));
            b2Body* b = MakeBullet(sim, b2Vec2(Fixed(-10) + phase, Fixed::FromRatio(k - 8, 4)), b2Vec2(kMaxSpeed, 0));
            bool tunnel = false;
            for (int i = 0; i < 30 && !tunnel; ++i) {
                sim.Step();
                tunnel = b->GetPosition().x > Fixed(10.05);
            }
            wallTunnels += tunnel;
        }
        {
            // Five 1 m boxes stacked at x = 10 on a ground box; the shot aims at box k % 5.
            Sim sim(r);
            b2Body* ground = sim.GroundBox(30, Fixed(0.5), b2Vec2(0, Fixed(-0.5)));
            for (int i = 0; i < 5; ++i) sim.Box(b2Vec2(10, Fixed::FromRatio(1 + 2 * i, 2)), Fixed(0.5), Fixed(0.5), 1);
            b2Body* b =
                MakeBullet(sim, b2Vec2(Fixed(-10) + phase, Fixed::FromRatio(1 + 2 * (k % 5), 2)), b2Vec2(kMaxSpeed, 0));
            HitListener hits(b, ground);
            sim.world().SetContactListener(&hits);
            bool tunnel = false;
            for (int i = 0; i < 30 && !tunnel; ++i) {
                sim.Step();
                // Past the stack's far face (10.5 m plus the bullet radius) with no contact.
                tunnel = !hits.hit && b->GetPosition().x > Fixed(10.625);
            }
            sim.world().SetContactListener(nullptr);
            stackTunnels += tunnel;
        }
        {
            // A zig-zag chain from x -20 to 20 (vertices every 2 m at heights 0 and 0.5), hit at
            // 45 degrees downward.
            Sim sim(r);
            b2Vec2 v[21];
            for (int i = 0; i < 21; ++i) v[i] = b2Vec2(-20 + 2 * i, (i % 2) ? Fixed(0.5) : Fixed());
            b2BodyDef gd;
            b2Body* ground = sim.world().CreateBody(&gd);
            b2ChainShape chain;
            chain.CreateChain(v, 21);
            ground->CreateFixture(&chain, 0);
            b2Body* b = MakeBullet(sim, b2Vec2(Fixed(-15) + phase, 10), b2Vec2(kDiagonal, -kDiagonal));
            bool tunnel = false;
            for (int i = 0; i < 30 && !tunnel; ++i) {
                sim.Step();
                const double x = D(b->GetPosition().x), yb = D(b->GetPosition().y);
                if (x <= -20 || x >= 20) continue;
                // Terrain height under the centre (display-only interpolation).
                const int seg = static_cast<int>(std::floor((x + 20) / 2));
                const double t = (x + 20) / 2 - seg;
                const double y0 = (seg % 2) ? 0.5 : 0.0, y1 = (seg % 2) ? 0.0 : 0.5;
                tunnel = yb < y0 + (y1 - y0) * t;
            }
            terrainTunnels += tunnel;
        }
    }
    Check(r, "wall_tunnels", wallTunnels, 0);
    Check(r, "stack_tunnels", stackTunnels, 0);
    Check(r, "terrain_tunnels", terrainTunnels, 0);
}

// 8. Fifty 1 m boxes spawned in a 10 x 5 grid at 0.6 m spacing (each overlaps its neighbours by
// 0.4 m) inside an open container.
void OverlapRecovery(CaseReport& r, Budget) {
    // Limits: the overlap is removed by position correction only (2.2.1 adds no velocity for
    // it), at most b2_maxLinearCorrection (0.2 m) per iteration and a baumgarte fraction (0.2)
    // of the rest, so separation is gradual: measured, the largest penetration first drops
    // below 4 slop (0.02 m) after 130 steps. Bound: 180 steps (3 s). The pile must stay calm:
    // measured 0.11 m/s, bound 1 m/s. At the end every contact is within 4 slop.
    constexpr double kSeparated = 4 * 328.0 / 65536.0;
    constexpr int kSteps = 600;
    Sim sim(r);
    sim.GroundBox(8, Fixed(0.5), b2Vec2(0, Fixed(-0.5)));
    sim.GroundBox(Fixed(0.5), 10, b2Vec2(Fixed(-7.5), 10));
    sim.GroundBox(Fixed(0.5), 10, b2Vec2(Fixed(7.5), 10));
    for (int row = 0; row < 5; ++row)
        for (int c = 0; c < 10; ++c)
            sim.Box(b2Vec2(Fixed::FromRatio(-27 + 6 * c, 10), Fixed::FromRatio(5 + 6 * row, 10)), Fixed(0.5),
                    Fixed(0.5), 1);
    int separatedStep = -1;
    double maxSpeed = 0;
    for (int i = 0; i < kSteps; ++i) {
        sim.Step();
        maxSpeed = std::max(maxSpeed, MaxSpeed(sim.world()));
        if (separatedStep < 0 && MaxPenetration(sim.world()) <= kSeparated) separatedStep = i + 1;
    }
    Check(r, "separation_step", separatedStep < 0 ? kSteps + 1 : separatedStep, 180);
    Check(r, "max_speed_mps", maxSpeed, 1);
    Check(r, "final_max_pen_m", MaxPenetration(sim.world()), kSeparated);
}

// 11. One hundred circles (r 0.25, density 1, friction 0, restitution 1) dropped in a closed
// 10 m box. Energy (kinetic + potential above the floor) is sampled after every step.
void RestitutionPile(CaseReport& r, Budget) {
    // Limit: the total never exceeds its initial value by more than 25 % over the 15 s, judged
    // on the median of 16 starts (the last circle moved sideways by 0 to 2.5 mm), because the
    // pile is chaotic: over 60 such starts one run's gain ranged from 15 % to 39 % (float Box2D
    // 2.4.1: 12 % to 28 %). 2.2.1's model gains energy here: restitution 1 re-uses the approach
    // speed with no loss, and position correction lifts overlapping circles in the pile
    // (potential energy from nothing, about one slop per contact per step). Medians of the 16
    // starts: lockbox +20.5 % (+21.8 % before Q32.32 velocities), float Box2D +18.8 %.
    constexpr double kGravity = 10;
    constexpr int kStarts = 16;
    auto run = [&](Fixed shift) {
        Sim sim(r);
        sim.GroundBox(6, Fixed(0.5), b2Vec2(0, Fixed(-0.5)));
        sim.GroundBox(6, Fixed(0.5), b2Vec2(0, Fixed(10.5)));
        sim.GroundBox(Fixed(0.5), 6, b2Vec2(Fixed(-5.5), 5));
        sim.GroundBox(Fixed(0.5), 6, b2Vec2(Fixed(5.5), 5));
        for (int row = 0; row < 10; ++row)
            for (int c = 0; c < 10; ++c) {
                const Fixed x = Fixed::FromRatio(-405 + 90 * c + 5 * (row % 2), 100);
                sim.Ball(b2Vec2(row == 9 && c == 9 ? x + shift : x, Fixed::FromRatio(100 + 85 * row, 100)), Fixed(0.25),
                         1, Fixed(), 1);
            }
        const double e0 = Energy(sim.world(), kGravity);
        double worst = 0;
        for (int i = 0; i < 900; ++i) {
            sim.Step();
            worst = std::max(worst, (Energy(sim.world(), kGravity) - e0) / e0);
        }
        return std::vector<double>{worst};
    };
    Check(r, "median_max_energy_gain_rel", EnsembleMedians(kStarts, run)[0], 0.25);
}

}  // namespace lockbox::stability::detail
