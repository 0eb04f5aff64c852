// The suite's registry, the Sim world wrapper, display-only measurements and the line and
// table formats.

#include "Harness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lockbox/scenes/LockboxScenes.h"

namespace lockbox::stability {
namespace detail {

Sim::Sim(CaseReport& r, const b2Vec2& gravity) : report_(r), world_(std::make_unique<b2World>(gravity)) {
    world_->SetHeadroomTelemetry(true);
}

void Sim::Step(int velocityIterations, int positionIterations) {
    world_->Step(kDt, velocityIterations, positionIterations);
    report_.headroom.Merge(world_->GetProfile().headroom);
    ++report_.steps;
}

b2Body* Sim::GroundBox(Fixed hx, Fixed hy, const b2Vec2& center) {
    b2BodyDef bd;
    b2Body* g = world_->CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(hx, hy, center, Fixed());
    g->CreateFixture(&box, 0);
    return g;
}

b2Body* Sim::GroundEdge(const b2Vec2& a, const b2Vec2& b) {
    b2BodyDef bd;
    b2Body* g = world_->CreateBody(&bd);
    b2EdgeShape edge;
    edge.Set(a, b);
    g->CreateFixture(&edge, 0);
    return g;
}

b2Body* Sim::Box(const b2Vec2& p, Fixed hx, Fixed hy, Fixed density, Fixed friction) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position = p;
    b2Body* b = world_->CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(hx, hy);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.density = density;
    fd.friction = friction;
    b->CreateFixture(&fd);
    return b;
}

b2Body* Sim::Ball(const b2Vec2& p, Fixed r, Fixed density, Fixed friction, Fixed restitution) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position = p;
    b2Body* b = world_->CreateBody(&bd);
    b2CircleShape circle;
    circle.m_radius = r;
    b2FixtureDef fd;
    fd.shape = &circle;
    fd.density = density;
    fd.friction = friction;
    fd.restitution = restitution;
    b->CreateFixture(&fd);
    return b;
}

double MaxSpeed(const b2World& w) {
    double s = 0;
    for (const b2Body* b = w.GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() != b2_dynamicBody) continue;
        const double vx = D(b->GetLinearVelocity().x), vy = D(b->GetLinearVelocity().y);
        s = std::max(s, std::sqrt(vx * vx + vy * vy));
    }
    return s;
}

double MaxPenetration(b2World& w) {
    double pen = 0;
    for (b2Contact* c = w.GetContactList(); c; c = c->GetNext()) {
        if (!c->IsTouching() || !c->IsEnabled()) continue;
        b2WorldManifold wm;
        c->GetWorldManifold(&wm);
        for (int32 i = 0; i < c->GetManifold()->pointCount; ++i) pen = std::max(pen, -D(wm.separations[i]));
    }
    return pen;
}

bool AllAsleep(const b2World& w) {
    for (const b2Body* b = w.GetBodyList(); b; b = b->GetNext())
        if (b->GetType() == b2_dynamicBody && b->IsAwake()) return false;
    return true;
}

double Energy(const b2World& w, double g) {
    double e = 0;
    for (const b2Body* b = w.GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() != b2_dynamicBody) continue;
        // Rotational energy about the centre of mass: GetInertia() is about the origin.
        const b2Vec2 lc = b->GetLocalCenter();
        const double m = D(b->GetMass());
        const double i = D(b->GetInertia()) - m * (D(lc.x) * D(lc.x) + D(lc.y) * D(lc.y));
        const double vx = D(b->GetLinearVelocity().x), vy = D(b->GetLinearVelocity().y);
        const double om = D(b->GetAngularVelocity());
        e += 0.5 * m * (vx * vx + vy * vy) + 0.5 * i * om * om + m * g * D(b->GetWorldCenter().y);
    }
    return e;
}

void Check(CaseReport& r, std::string_view metric, double value, double limit, bool limitation) {
    CaseResult c;
    c.name = r.name;
    c.metric = std::string(metric);
    c.value = value;
    c.limit = limit;
    c.pass = value <= limit;
    c.limitation = limitation;
    r.results.push_back(std::move(c));
}

std::vector<double> EnsembleMedians(int starts, const std::function<std::vector<double>(Fixed shift)>& run) {
    std::vector<std::vector<double>> byFigure;
    for (int k = 0; k < starts; ++k) {
        const std::vector<double> figures = run(Fixed::FromRaw(k * kEnsembleShift.Raw()));
        if (byFigure.empty()) byFigure.resize(figures.size());
        for (size_t i = 0; i < figures.size(); ++i) byFigure[i].push_back(figures[i]);
    }
    std::vector<double> medians;
    for (std::vector<double>& v : byFigure) {
        std::sort(v.begin(), v.end());
        const size_t n = v.size();
        medians.push_back(n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2);
    }
    return medians;
}

}  // namespace detail

namespace {

using CaseFn = void (*)(CaseReport&, Budget);

struct Entry {
    CaseInfo info;
    CaseFn fn;
};

const std::vector<Entry>& Entries() {
    using namespace detail;
    static const std::vector<Entry> entries = {
        {{1, "tall_stack", "20 boxes of 0.5 m settle and sleep", false}, TallStack},
        {{2, "pyramids", "pyramids with bases 20 and 40 hold for 1200 steps", true}, Pyramids},
        {{3, "tiny_bodies", "0.1 m boxes at density 0.1 and 0.1 m circles come to rest", false}, TinyBodies},
        {{4, "large_bodies", "ten 10 m boxes at density 10 on a 50 m ground", false}, LargeBodies},
        {{5, "mass_ratios", "10:1, 100:1 and 1000:1 pairs and stacks", false}, MassRatios},
        {{6, "wrecking_ball", "a heavy ball on a 30-link light chain", false}, WreckingBall},
        {{7, "bullets", "0.25 m bullets at the maximum speed: no tunnelling", false}, Bullets},
        {{8, "overlap_recovery", "50 boxes spawned overlapping separate calmly", false}, OverlapRecovery},
        {{9, "far_from_origin", "library scenes moved by whole metres: bit-exact relative motion", true},
         FarFromOrigin},
        {{10, "long_runs", "30 min spin, +-10 turn limit, 10 min creep, free fall out of bounds", true}, LongRuns},
        {{11, "restitution_pile", "100 circles with restitution 1: energy bound", false}, RestitutionPile},
        {{12, "degenerate_input", "degenerate polygons are rejected or simulate stably", false}, DegenerateInput},
        {{13, "pulley_gear", "the pulley's singular case and a gear chain stay bounded", false}, PulleyGear},
        {{14, "soft_joints", "0.1 and 29 Hz springs on 0.01 and 1000 kg; mouse at 1000 m", false}, SoftJoints},
        {{15, "sleep_threshold", "0.0099 m/s sleeps, 0.0101 m/s stays awake", false}, SleepThreshold},
    };
    return entries;
}

}  // namespace

bool CaseReport::Passed() const noexcept {
    for (const CaseResult& r : results)
        if (!r.pass) return false;
    return !results.empty();
}

const std::vector<CaseInfo>& AllCases() {
    static const std::vector<CaseInfo> infos = [] {
        std::vector<CaseInfo> v;
        for (const Entry& e : Entries()) v.push_back(e.info);
        return v;
    }();
    return infos;
}

CaseReport RunCase(std::string_view name, Budget budget) {
    CaseReport r;
    r.name = std::string(name);
    for (const Entry& e : Entries()) {
        if (e.info.name != name) continue;
        e.fn(r, budget);
        // Every case also promises that nothing saturated (a checked build traps instead).
        detail::Check(r, "saturations", static_cast<double>(r.headroom.saturations), 0);
        return r;
    }
    detail::Check(r, "unknown_case", 1, 0);
    return r;
}

std::vector<CaseReport> RunAllCases(Budget budget) {
    std::vector<CaseReport> out;
    for (const CaseInfo& c : AllCases()) out.push_back(RunCase(c.name, budget));
    return out;
}

std::string FormatLine(const CaseResult& r) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "case=%s metric=%s value=%.6g limit=%.6g %s%s", r.name.c_str(), r.metric.c_str(),
                  r.value, r.limit, r.pass ? "PASS" : "FAIL", r.limitation ? " (limitation)" : "");
    return buf;
}

SceneHeadroom MeasureSceneHeadroom(std::string_view scene, int steps) {
    SceneHeadroom out;
    out.scene = std::string(scene);
    auto s = scenes::MakeLockboxScene(scene);
    if (!s) return out;
    scenes::LockboxEngine e;
    e.world().SetHeadroomTelemetry(true);
    const scenes::RunSettings settings;
    const scenes::Resolved r = scenes::Resolve(s->Info(), settings);
    scenes::ConfigureWorld(e, s->Info(), settings);
    s->Prepare(r);
    s->Build(e);
    const int n = steps >= 0 ? steps : r.steps;
    for (int i = 0; i < n; ++i) {
        s->BeforeStep(e, i);
        e.Step(r.hz, r.velocityIterations, r.positionIterations);
        out.headroom.Merge(e.world().GetProfile().headroom);
    }
    out.steps = n;
    return out;
}

std::string HeadroomTableHeader() {
    std::string h = "scene/case                ";
    for (int32 i = 0; i < static_cast<int32>(b2HeadroomClass::e_count); ++i) {
        char buf[32];
        std::snprintf(buf, sizeof buf, " %10.10s", b2HeadroomClassName(static_cast<b2HeadroomClass>(i)));
        h += buf;
    }
    return h + "  saturations";
}

std::string HeadroomTableRow(std::string_view label, const b2Headroom& h) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%-26.26s", std::string(label).c_str());
    std::string row = buf;
    for (int32 i = 0; i < static_cast<int32>(b2HeadroomClass::e_count); ++i) {
        std::snprintf(buf, sizeof buf, " %10.2e", h.entries[i].Fraction());
        row += buf;
    }
    std::snprintf(buf, sizeof buf, "  %lld", static_cast<long long>(h.saturations));
    return row + buf;
}

}  // namespace lockbox::stability
