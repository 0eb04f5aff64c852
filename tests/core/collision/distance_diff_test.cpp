// Differential test of lockbox's b2Distance and b2TimeOfImpact against float Box2D 2.4.1.
//
// Random shape pairs are built in Q16.16; float Box2D runs on the very same geometry (every
// Fixed input converted exactly to float: all coordinates stay below 256 m, where float has
// the 24 bits a Q16.16 value needs). Disagreements are counted per pair type and class,
// printed, and must stay at or below 0.1 % per type.
//
// This file is also the body of heavy/distance_diff_heavy_test.cpp, which includes it with
// LOCKBOX_DISTANCE_DIFF_PAIRS set to 10000.

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "FixedPrint.h"
#include "lockbox/collision/Distance.h"
#include "lockbox/collision/TimeOfImpact.h"

// Box2D 2.4.1 defines b2_linearSlop, b2_polygonRadius... as macros: capture lockbox's values
// before its header is seen.
namespace lockbox::diff {
inline constexpr Fixed kPolygonRadius = b2_polygonRadius;
inline constexpr double kLinearSlopFloat = 0.005;
}  // namespace lockbox::diff

#include "Box2DFloat.h"  // float Box2D without its constant macros

#ifndef LOCKBOX_DISTANCE_DIFF_PAIRS
#define LOCKBOX_DISTANCE_DIFF_PAIRS 500
#endif
// The heavy suite names its tests apart: ctest keys labels by test name, and a shared name let
// the heavy run's label exclude the fast run from every preset that skips heavy tests.
#ifndef LOCKBOX_DISTANCE_DIFF_SUITE
#define LOCKBOX_DISTANCE_DIFF_SUITE DistanceDiff
#define LOCKBOX_TOI_DIFF_SUITE ToiDiff
#endif

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

constexpr int kPairs = LOCKBOX_DISTANCE_DIFF_PAIRS;
constexpr double kDistanceTol = 1e-3;  // m, distance and witness points
constexpr double kTimeTol = 1e-3;      // sweep fraction

enum Kind { kCircle, kPolygon, kEdge };

// One shape in both number systems. Not copyable once proxies point into it.
struct DualShape {
    Kind kind = kCircle;
    std::array<b2Vec2, 8> v;
    std::array<::b2Vec2, 8> fv;
    int count = 0;
    Fixed radius;

    b2DistanceProxy Proxy() const {
        b2DistanceProxy p;
        p.Set(v.data(), count, radius);
        return p;
    }
    ::b2DistanceProxy FloatProxy() const {
        ::b2DistanceProxy p;
        p.Set(fv.data(), count, static_cast<float>(radius.ToDouble()));
        return p;
    }
    void Finish() {
        for (int i = 0; i < count; ++i) fv[static_cast<size_t>(i)] = ToFloat(v[static_cast<size_t>(i)]);
    }
    static ::b2Vec2 ToFloat(const b2Vec2& p) { return ::b2Vec2(p.x.ToFloat(), p.y.ToFloat()); }
};

class Rng {
public:
    explicit Rng(uint64_t seed) : engine_(seed) {}
    // Uniform raw value in [lo, hi] (inclusive), platform-independent.
    int32_t Raw(int32_t lo, int32_t hi) {
        const uint64_t span = static_cast<uint64_t>(int64_t{hi} - lo) + 1;
        return static_cast<int32_t>(lo + static_cast<int64_t>(engine_() % span));
    }
    Fixed Range(double lo, double hi) {
        return Fixed::FromRaw(Raw(static_cast<int32_t>(lo * 65536), static_cast<int32_t>(hi * 65536)));
    }
    int Int(int lo, int hi) { return Raw(lo, hi); }
    // A point drawn y first, then x. The cases were first drawn inside calls, whose arguments
    // are evaluated in an unspecified order (GCC went right to left, Clang left to right), so
    // each compiler tested other cases; the draws are now in sequence, in GCC's old order, so
    // that every compiler tests the cases the tolerances were set on.
    b2Vec2 Point(double lo, double hi) {
        const Fixed y = Range(lo, hi);
        const Fixed x = Range(lo, hi);
        return b2Vec2(x, y);
    }

private:
    std::mt19937_64 engine_;
};

void MakeCircle(Rng& rng, DualShape* s) {
    s->kind = kCircle;
    s->count = 1;
    s->v[0] = rng.Point(-0.5, 0.5);
    s->radius = rng.Range(0.05, 1.5);
    s->Finish();
}

void MakePolygon(Rng& rng, DualShape* s) {
    s->kind = kPolygon;
    s->radius = diff::kPolygonRadius;
    const b2Vec2 center = rng.Point(-0.3, 0.3);
    const b2Rot rot(rng.Range(-3.1, 3.1));
    const Fixed rx = rng.Range(0.1, 1.5), ry = rng.Range(0.1, 1.5);
    if (rng.Int(0, 3) == 0) {
        // A box: parallel faces make the witness points of face-to-face pairs ambiguous.
        s->count = 4;
        const b2Vec2 corners[4] = {{-rx, -ry}, {rx, -ry}, {rx, ry}, {-rx, ry}};
        for (int i = 0; i < 4; ++i) s->v[static_cast<size_t>(i)] = center + b2Mul(rot, corners[i]);
    } else {
        // Points on an ellipse at jittered, increasing angles: always strictly convex.
        s->count = rng.Int(3, 8);
        const int32_t sector = 411775 / s->count;
        for (int i = 0; i < s->count; ++i) {
            const Fixed angle = Fixed::FromRaw(i * sector + rng.Raw(-sector * 3 / 10, sector * 3 / 10));
            const b2Rot dir(angle);
            s->v[static_cast<size_t>(i)] = center + b2Mul(rot, b2Vec2(rx * dir.c, ry * dir.s));
        }
    }
    s->Finish();
}

void MakeEdge(Rng& rng, DualShape* s) {
    s->kind = kEdge;
    s->count = 2;
    s->radius = diff::kPolygonRadius;
    s->v[0] = rng.Point(-2, 2);
    const b2Rot dir(rng.Range(-3.1, 3.1));
    const Fixed length = rng.Range(0.1, 3);
    s->v[1] = s->v[0] + b2Vec2(length * dir.c, length * dir.s);
    s->Finish();
}

void Make(Rng& rng, Kind kind, DualShape* s) {
    if (kind == kCircle) MakeCircle(rng, s);
    if (kind == kPolygon) MakePolygon(rng, s);
    if (kind == kEdge) MakeEdge(rng, s);
}

::b2Transform ToFloat(const b2Transform& xf) {
    ::b2Transform f;
    f.p = DualShape::ToFloat(xf.p);
    f.q.s = xf.q.s.ToFloat();
    f.q.c = xf.q.c.ToFloat();
    return f;
}

::b2Sweep ToFloat(const b2Sweep& s) {
    ::b2Sweep f;
    f.localCenter = DualShape::ToFloat(s.localCenter);
    f.c0 = DualShape::ToFloat(s.c0);
    f.c = DualShape::ToFloat(s.c);
    f.a0 = s.a0.ToFloat();
    f.a = s.a.ToFloat();
    f.alpha0 = s.alpha0.ToFloat();
    return f;
}

double Dist(const b2Vec2& a, const ::b2Vec2& b) { return std::hypot(a.x.ToDouble() - b.x, a.y.ToDouble() - b.y); }

// True when world point p lies in the core (vertex hull, no radius) of shape s placed at xf,
// within `slack` metres. For overlapping cores any such common point is a valid GJK answer.
bool InCore(const DualShape& s, const b2Transform& xf, const b2Vec2& p, double slack) {
    const double px = p.x.ToDouble(), py = p.y.ToDouble();
    double wx[8], wy[8];
    for (int i = 0; i < s.count; ++i) {
        const b2Vec2 w = b2Mul(xf, s.v[static_cast<size_t>(i)]);
        wx[i] = w.x.ToDouble();
        wy[i] = w.y.ToDouble();
    }
    if (s.count == 1) return std::hypot(px - wx[0], py - wy[0]) <= slack;
    if (s.count == 2) {
        const double ex = wx[1] - wx[0], ey = wy[1] - wy[0];
        double t = ((px - wx[0]) * ex + (py - wy[0]) * ey) / (ex * ex + ey * ey);
        t = std::min(1.0, std::max(0.0, t));
        return std::hypot(px - wx[0] - t * ex, py - wy[0] - t * ey) <= slack;
    }
    for (int i = 0; i < s.count; ++i) {
        const int j = (i + 1) % s.count;
        const double ex = wx[j] - wx[i], ey = wy[j] - wy[i];
        const double side = (ex * (py - wy[i]) - ey * (px - wx[i])) / std::hypot(ex, ey);
        if (side < -slack) return false;
    }
    return true;
}

struct PairType {
    const char* name;
    Kind a, b;
};
constexpr PairType kTypes[] = {{"circle/circle", kCircle, kCircle},
                               {"circle/polygon", kCircle, kPolygon},
                               {"polygon/polygon", kPolygon, kPolygon},
                               {"edge/polygon", kEdge, kPolygon},
                               {"edge/circle", kEdge, kCircle}};

// Per-type tallies; the class names are the keys printed in the summary.
struct Tally {
    int checks = 0;
    int disagreements = 0;
    std::map<std::string, int> classes;
    void Add(const std::string& cls, bool isDisagreement) {
        ++classes[cls];
        if (isDisagreement) ++disagreements;
    }
};

void PrintTally(const char* what, const char* type, const Tally& t) {
    std::printf("[%s] %-16s checks %6d  disagreements %4d (%.3f %%)", what, type, t.checks, t.disagreements,
                100.0 * t.disagreements / (t.checks ? t.checks : 1));
    for (const auto& [name, n] : t.classes) std::printf("  %s: %d", name.c_str(), n);
    std::printf("\n");
}

// ---- b2Distance ------------------------------------------------------------------------------

TEST(LOCKBOX_DISTANCE_DIFF_SUITE, AgainstFloatBox2D) {
    for (int type = 0; type < 5; ++type) {
        const PairType& pt = kTypes[type];
        Rng rng(0xD15u + static_cast<uint64_t>(type) * 7919u);
        Tally tally;
        int printed = 0, overlapping = 0;
        double maxDistanceDiff = 0, maxPointDiff = 0;
        for (int pair = 0; pair < kPairs; ++pair) {
            DualShape sa, sb;
            Make(rng, pt.a, &sa);
            Make(rng, pt.b, &sb);
            b2Transform xfA, xfB;
            // Each transform's angle is drawn before its position (GCC's old order, as above).
            const Fixed angleA = rng.Range(-3.14, 3.14);
            xfA.Set(rng.Point(-4, 4), angleA);
            const Fixed angleB = rng.Range(-3.14, 3.14);
            xfB.Set(xfA.p + rng.Point(-4, 4), angleB);
            // Three checks per pair: the random placement without and with radii, then B moved
            // along the witness direction to a near-contact placement (core gap -20..+20 mm),
            // where GJK meets its degenerate cases (origin on or near the simplex boundary).
            for (int mode = 0; mode < 3; ++mode) {
                const int useRadii = mode == 1 ? 1 : 0;
                if (mode == 2) {
                    b2DistanceInput probe;
                    probe.proxyA = sa.Proxy();
                    probe.proxyB = sb.Proxy();
                    probe.transformA = xfA;
                    probe.transformB = xfB;
                    b2SimplexCache probeCache;
                    b2DistanceOutput probeOut;
                    b2Distance(&probeOut, &probeCache, &probe);
                    b2Vec2 n = probeOut.pointB - probeOut.pointA;
                    n.Normalize();
                    const Fixed move = probeOut.distance - rng.Range(-0.02, 0.02);
                    xfB.p -= move * n;
                }
                b2DistanceInput in;
                in.proxyA = sa.Proxy();
                in.proxyB = sb.Proxy();
                in.transformA = xfA;
                in.transformB = xfB;
                in.useRadii = useRadii != 0;
                b2SimplexCache cache;
                b2DistanceOutput out;
                b2Distance(&out, &cache, &in);

                ::b2DistanceInput fin;
                fin.proxyA = sa.FloatProxy();
                fin.proxyB = sb.FloatProxy();
                fin.transformA = ToFloat(xfA);
                fin.transformB = ToFloat(xfB);
                fin.useRadii = useRadii != 0;
                ::b2SimplexCache fcache;
                fcache.count = 0;
                ::b2DistanceOutput fout;
                ::b2Distance(&fout, &fcache, &fin);

                ++tally.checks;
                const double dd = std::fabs(out.distance.ToDouble() - fout.distance);
                const double da = Dist(out.pointA, fout.pointA), db = Dist(out.pointB, fout.pointB);
                if (out.distance == Fixed()) ++overlapping;
                maxDistanceDiff = std::max(maxDistanceDiff, dd);
                maxPointDiff = std::max(maxPointDiff, std::max(da, db));
                std::string cls;
                if (dd > kDistanceTol) {
                    cls = "distance";
                } else if (da > kDistanceTol || db > kDistanceTol) {
                    if (fout.distance < 1e-3 && out.distance == Fixed()) {
                        // Overlapping cores: GJK stops in any triangle that holds the origin.
                        const bool inside = InCore(sa, xfA, out.pointA, 1e-4) && InCore(sb, xfB, out.pointA, 1e-4);
                        cls = inside ? "witness(overlap), point in both cores" : "witness(overlap), point OUTSIDE";
                    } else {
                        cls = "witness(separated)";
                    }
                }
                if (cls.empty()) continue;
                tally.Add(cls, true);
                if (printed++ < 8) {
                    std::printf(
                        "  %s #%d mode=%d %s: lockbox d=%.6f pA=(%.5f,%.5f) pB=(%.5f,%.5f) it=%d | "
                        "float d=%.6f pA=(%.5f,%.5f) pB=(%.5f,%.5f) it=%d\n",
                        pt.name, pair, mode, cls.c_str(), out.distance.ToDouble(), out.pointA.x.ToDouble(),
                        out.pointA.y.ToDouble(), out.pointB.x.ToDouble(), out.pointB.y.ToDouble(), out.iterations,
                        fout.distance, fout.pointA.x, fout.pointA.y, fout.pointB.x, fout.pointB.y, fout.iterations);
                }
            }
        }
        PrintTally("distance", pt.name, tally);
        std::printf("           zero distance %d, max |d - d_float| %.3g m, max witness gap %.3g m\n", overlapping,
                    maxDistanceDiff, maxPointDiff);
        EXPECT_LE(tally.disagreements * 1000, tally.checks) << pt.name;
    }
}

// ---- b2TimeOfImpact ---------------------------------------------------------------------------

b2Sweep RandomSweep(Rng& rng) {
    b2Sweep s;
    s.localCenter = rng.Point(-0.2, 0.2);
    s.c0 = rng.Point(-3, 3);
    s.c = rng.Point(-3, 3);
    s.a0 = rng.Range(-3.14, 3.14);
    s.a = s.a0 + rng.Range(-1.5, 1.5);
    s.alpha0 = Fixed();
    return s;
}

// Float core distance at time t of the float sweeps.
double FloatDistanceAt(const ::b2DistanceProxy& a, const ::b2Sweep& sa, const ::b2DistanceProxy& b, const ::b2Sweep& sb,
                       double t) {
    ::b2DistanceInput in;
    in.proxyA = a;
    in.proxyB = b;
    sa.GetTransform(&in.transformA, static_cast<float>(t));
    sb.GetTransform(&in.transformB, static_cast<float>(t));
    in.useRadii = false;
    ::b2SimplexCache cache;
    cache.count = 0;
    ::b2DistanceOutput out;
    ::b2Distance(&out, &cache, &in);
    return out.distance;
}

const char* StateName(int s) {
    static const char* names[] = {"unknown", "failed", "overlapped", "touching", "separated"};
    return names[s];
}

TEST(LOCKBOX_TOI_DIFF_SUITE, AgainstFloatBox2D) {
    for (int type = 0; type < 5; ++type) {
        const PairType& pt = kTypes[type];
        Rng rng(0x701u + static_cast<uint64_t>(type) * 104729u);
        Tally tally;
        int printed = 0, states[5] = {0, 0, 0, 0, 0}, maxIter = 0, maxRoot = 0;
        double maxDt = 0;
        for (int pair = 0; pair < kPairs; ++pair) {
            DualShape sa, sb;
            Make(rng, pt.a, &sa);
            Make(rng, pt.b, &sb);
            b2TOIInput in;
            in.proxyA = sa.Proxy();
            in.proxyB = sb.Proxy();
            in.sweepA = RandomSweep(rng);
            in.sweepB = RandomSweep(rng);
            in.tMax = rng.Int(0, 3) == 0 ? rng.Range(0.5, 1) : Fixed(1);
            b2TOIOutput out;
            b2TimeOfImpact(&out, &in);

            ::b2TOIInput fin;
            fin.proxyA = sa.FloatProxy();
            fin.proxyB = sb.FloatProxy();
            fin.sweepA = ToFloat(in.sweepA);
            fin.sweepB = ToFloat(in.sweepB);
            fin.tMax = in.tMax.ToFloat();
            ::b2TOIOutput fout;
            ::b2TimeOfImpact(&fout, &fin);

            ++tally.checks;
            const double tl = out.t.ToDouble(), tf = fout.t;
            ++states[out.state];
            maxIter = std::max(maxIter, static_cast<int>(out.iterations));
            maxRoot = std::max(maxRoot, static_cast<int>(out.rootIterations));
            if (out.state == static_cast<int>(fout.state)) maxDt = std::max(maxDt, std::fabs(tl - tf));
            std::string cls;
            bool bad = false;
            if (static_cast<int>(out.state) != static_cast<int>(fout.state)) {
                cls = std::string("state ") + StateName(out.state) + "/" + StateName(fout.state);
                bad = true;
            } else if (std::fabs(tl - tf) > kTimeTol) {
                // Both may be valid: on a grazing approach the separation changes slowly and the
                // accepted band target +- tolerance spans a long time. Check lockbox's t with float
                // Box2D: the shapes must be in the band at t and never below it before t.
                const double radius = sa.radius.ToDouble() + sb.radius.ToDouble();
                const double target = std::max(diff::kLinearSlopFloat, radius - 3 * diff::kLinearSlopFloat),
                             tol = 0.25 * diff::kLinearSlopFloat, slack = 2e-4;
                ::b2Sweep fa = fin.sweepA, fb = fin.sweepB;
                fa.Normalize();
                fb.Normalize();
                const double dAt = FloatDistanceAt(fin.proxyA, fa, fin.proxyB, fb, tl);
                bool valid =
                    out.state == b2TOIOutput::e_touching && dAt > target - tol - slack && dAt < target + tol + slack;
                for (int k = 0; valid && k < 64; ++k) {
                    valid = FloatDistanceAt(fin.proxyA, fa, fin.proxyB, fb, tl * k / 64.0) > target - tol - slack;
                }
                cls = valid ? "t differs, lockbox t verified" : "t differs";
                bad = !valid;
            }
            if (cls.empty()) continue;
            tally.Add(cls, bad);
            if (bad && printed++ < 8) {
                std::printf("  %s #%d %s: lockbox %s t=%.6f it=%d | float %s t=%.6f\n", pt.name, pair, cls.c_str(),
                            StateName(out.state), tl, out.iterations, StateName(fout.state), tf);
            }
        }
        PrintTally("toi", pt.name, tally);
        std::printf(
            "      states failed %d overlapped %d touching %d separated %d; max |t - t_float| %.3g, "
            "max iterations %d, max root iterations per call %d\n",
            states[1], states[2], states[3], states[4], maxDt, maxIter, maxRoot);
        EXPECT_LE(tally.disagreements * 1000, tally.checks) << pt.name;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
