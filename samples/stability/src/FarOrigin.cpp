// Case 9: far from the origin. Every library scene is built twice, once where it stands and
// once moved by a whole number of metres, and the two are stepped side by side. After every
// step each body's position minus the offset, its angle and its velocities must equal the
// reference's bit for bit (ARCHITECTURE §5: precision is the same everywhere in the world).
//
// Moving a scene: after Build, every body gets SetTransform(position + offset, angle), and
// bodies a scene spawns later (rain) are moved right after they appear. Pulley joints keep
// world-space ground anchors, so they are re-created with moved anchors, in both worlds alike
// (the re-creation changes the joint order, which must match).

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "Harness.h"
#include "lockbox/scenes/LockboxScenes.h"

namespace lockbox::stability::detail {
namespace {

using scenes::LockboxEngine;

/// A scene whose own code compares absolute coordinates, so that moving its bodies changes
/// what the scene does (not what the engine does); it is listed, not compared.
/// one_sided_platform: its PreSolve compares an actor's y with the platform height it
/// recorded at build time.
bool SceneUsesAbsoluteCoordinates(std::string_view name) { return name == "one_sided_platform"; }

/// Moves every body not yet moved (moved[id] false) by off.
void MoveNewBodies(b2World& w, const b2Vec2& off, std::vector<bool>& moved) {
    for (b2Body* b = w.GetBodyList(); b; b = b->GetNext()) {
        const auto id = static_cast<size_t>(b->GetId());
        if (id >= moved.size()) moved.resize(id + 1, false);
        if (moved[id]) continue;
        moved[id] = true;
        if (off.x != Fixed() || off.y != Fixed()) b->SetTransform(b->GetPosition() + off, b->GetAngle());
    }
}

/// Re-creates every pulley joint with its ground anchors moved by off (zero: re-created as is).
void RecreatePulleys(b2World& w, const b2Vec2& off) {
    std::vector<b2Joint*> pulleys;
    for (b2Joint* j = w.GetJointList(); j; j = j->GetNext())
        if (j->GetType() == e_pulleyJoint) pulleys.push_back(j);
    for (b2Joint* j : pulleys) {
        const auto* p = static_cast<const b2PulleyJoint*>(j);
        b2PulleyJointDef pd;
        pd.Initialize(j->GetBodyA(), j->GetBodyB(), p->GetGroundAnchorA() + off, p->GetGroundAnchorB() + off,
                      p->GetAnchorA(), p->GetAnchorB(), p->GetRatio());
        pd.collideConnected = j->GetCollideConnected();
        w.DestroyJoint(j);
        w.CreateJoint(&pd);
    }
}

/// One scene world with its offset.
struct Copy {
    LockboxEngine engine;
    std::unique_ptr<scenes::LockboxScene> scene;
    b2Vec2 offset;
    std::vector<bool> moved;
};

/// Largest raw difference of the relative state over bodies (position minus offset, angle,
/// velocities); 0 when equal, INT32_MAX when the body lists differ in length.
int64_t MaxRelativeDiff(b2World& ref, const b2Vec2& refOff, b2World& moved, const b2Vec2& off) {
    int64_t diff = 0;
    auto d = [&diff](Fixed a, Fixed b) {
        const int64_t e = int64_t{a.Raw()} - b.Raw();
        diff = std::max(diff, e < 0 ? -e : e);
    };
    const b2Body* a = ref.GetBodyList();
    const b2Body* b = moved.GetBodyList();
    for (; a && b; a = a->GetNext(), b = b->GetNext()) {
        const b2Vec2 pa = a->GetPosition() - refOff, pb = b->GetPosition() - off;
        d(pa.x, pb.x);
        d(pa.y, pb.y);
        d(a->GetAngle(), b->GetAngle());
        d(a->GetLinearVelocity().x, b->GetLinearVelocity().x);
        d(a->GetLinearVelocity().y, b->GetLinearVelocity().y);
        d(a->GetAngularVelocity(), b->GetAngularVelocity());
        if (a->IsAwake() != b->IsAwake()) diff = std::max<int64_t>(diff, 1);
    }
    if (a || b) diff = INT32_MAX;
    return diff;
}

/// Outcome of stepping one scene at several placements side by side.
struct Comparison {
    bool ran = false;          ///< false when the scene is unavailable or skipped by the budget
    int firstMismatch = 0;     ///< first step whose relative state differs; 0 when none did
    int64_t firstDiffRaw = 0;  ///< largest raw difference at that step
};

/// Builds `name` at offsets[0] (the reference) and at each further offset, steps them side by
/// side for up to maxSteps (at most the scene's default), and compares the relative states
/// after every step.
Comparison ComparePlacements(CaseReport& r, std::string_view name, const std::vector<b2Vec2>& offsets, int maxSteps) {
    Comparison out;
    std::vector<std::unique_ptr<Copy>> copies;
    int steps = 0;
    for (const b2Vec2& off : offsets) {
        copies.push_back(std::make_unique<Copy>());
        Copy& c = *copies.back();
        c.offset = off;
        c.scene = scenes::MakeLockboxScene(name);
        if (!c.scene) return out;
        const auto& info = c.scene->Info();
        const scenes::RunSettings settings;
        const scenes::Resolved res = scenes::Resolve(info, settings);
        scenes::ConfigureWorld(c.engine, info, settings);
        c.engine.world().SetHeadroomTelemetry(true);
        c.scene->Prepare(res);
        c.scene->Build(c.engine);
        MoveNewBodies(c.engine.world(), c.offset, c.moved);
        RecreatePulleys(c.engine.world(), c.offset);
        steps = std::min(res.steps, maxSteps);
    }
    out.ran = true;
    const scenes::Resolved res = scenes::Resolve(copies[0]->scene->Info(), scenes::RunSettings{});
    for (int i = 0; i < steps && out.firstMismatch == 0; ++i) {
        for (auto& c : copies) {
            c->scene->BeforeStep(c->engine, i);
            MoveNewBodies(c->engine.world(), c->offset, c->moved);
            c->engine.Step(res.hz, res.velocityIterations, res.positionIterations);
            r.headroom.Merge(c->engine.world().GetProfile().headroom);
            ++r.steps;
        }
        for (size_t k = 1; k < copies.size(); ++k) {
            const int64_t d = MaxRelativeDiff(copies[0]->engine.world(), copies[0]->offset, copies[k]->engine.world(),
                                              copies[k]->offset);
            if (d != 0 && out.firstMismatch == 0) {
                out.firstMismatch = i + 1;
                out.firstDiffRaw = d;
            }
        }
    }
    return out;
}

/// The stage that breaks translation invariance, measured on its own: b2Mul(xf, v) - xf.p
/// with the frame at (3, 5) m and at (3, 5) - (15000, 15000) m, over 64 angles and 64 body
/// points (0.5 m vertices among them). Returns the largest raw difference (a tie rounded the
/// other way is 1 raw).
int64_t TransformTieDifference() {
    int64_t worst = 0;
    const b2Vec2 near(3, 5), far = b2Vec2(3, 5) - b2Vec2(15000, 15000);
    for (int k = 0; k < 64; ++k) {
        b2Transform a, b;
        a.q.Set(Fixed::FromRatio(k * 1571, 16000));  // 0 .. 6.3 rad in 64 steps
        b.q = a.q;
        a.p = near;
        b.p = far;
        for (int m = 0; m < 64; ++m) {
            const b2Vec2 v(Fixed::FromRatio((m % 8) - 4, 8) + Fixed::FromRaw(m), Fixed::FromRatio((m / 8) - 4, 8));
            const b2Vec2 da = b2Mul(a, v) - near, db = b2Mul(b, v) - far;
            for (const int64_t e : {int64_t{da.x.Raw()} - db.x.Raw(), int64_t{da.y.Raw()} - db.y.Raw()})
                worst = std::max(worst, e < 0 ? -e : e);
        }
    }
    return worst;
}

}  // namespace

void FarFromOrigin(CaseReport& r, Budget budget) {
    // Two findings shape this case (docs/stability.md, "Far from the origin"):
    // 1. Placements whose coordinates keep their signs are bit-exact: every scene, moved
    //    anywhere within one quadrant of the +-16000 m world, follows the same relative
    //    trajectory bit for bit. This is the promise, asserted per scene: the reference is the
    //    scene at (+-2000, +-2000) m (beyond every library scene's extent, so no coordinate
    //    changes sign) and the far copies sit at (+-15000, +-15000) and irregular offsets in the
    //    same quadrant.
    // 2. Moving a scene across an axis: b2Mul(b2Transform, b2Vec2) used to round R v + p in
    //    one go (ties rounded by the sign of the world coordinate) and the position solver
    //    halved pA + pB; both now round only translation-invariant quantities (R v, pB - pA).
    //    That fixed 8 of the 10 scenes that diverged; 2 remain in the full budget.
    struct Quadrant {
        b2Vec2 reference;
        std::vector<b2Vec2> far;
    };
    std::vector<Quadrant> quadrants = {{b2Vec2(2000, -2000), {b2Vec2(15000, -15000)}}};
    if (budget == Budget::full) {
        quadrants[0].far.push_back(b2Vec2(7919, -3001));
        quadrants.push_back({b2Vec2(-2000, 2000), {b2Vec2(-15000, 15000), b2Vec2(-4099, 12345)}});
    }
    int compared = 0, quadrantMismatches = 0, crossDiverged = 0;
    for (std::string_view name : scenes::AllSceneNames()) {
        if (SceneUsesAbsoluteCoordinates(name)) continue;
        const auto probe = scenes::MakeLockboxScene(name);
        if (!probe) continue;
        // Step budgets. The library's heavy scenes cost 0.2-0.7 s a step in a release build
        // and tumbler about 40 ms once its boxes pile up: the fast budget skips them and the
        // full one runs them for 10 steps in the first quadrant only. The other scenes run
        // 60 steps (fast: it must also fit the sanitizer build) or up to 240 (full).
        const bool expensive = probe->Info().heavy || name == "tumbler";
        if (budget == Budget::fast && expensive) continue;
        const int maxSteps = budget == Budget::fast ? 60 : (expensive ? 10 : 240);
        int firstMismatch = 0;
        for (size_t qi = 0; qi < (expensive ? 1 : quadrants.size()); ++qi) {
            const Quadrant& q = quadrants[qi];
            std::vector<b2Vec2> offsets = {q.reference};
            offsets.insert(offsets.end(), q.far.begin(),
                           q.far.begin() + (expensive ? 1 : static_cast<long>(q.far.size())));
            const Comparison c = ComparePlacements(r, name, offsets, maxSteps);
            if (c.firstMismatch != 0 && firstMismatch == 0) firstMismatch = c.firstMismatch;
        }
        ++compared;
        quadrantMismatches += firstMismatch != 0;
        // Per scene: the first step whose relative state differs within a quadrant (0: none).
        Check(r, std::string(name) + "_first_mismatch_step", firstMismatch, 0);
        const Comparison cross = ComparePlacements(r, name, {b2Vec2(0, 0), b2Vec2(15000, -15000)}, maxSteps);
        crossDiverged += cross.firstMismatch != 0;
    }
    Check(r, "same_quadrant_scenes_diverged", quadrantMismatches, 0);
    // Guard against a silently empty comparison (a scene list or registry change).
    Check(r, "scenes_not_compared", compared >= (budget == Budget::full ? 20 : 14) ? 0 : 1, 0);
    // Finding 2: b2Mul(b2Transform, b2Vec2) is translation invariant (measured directly on
    // tie-prone inputs) and no scene diverges across the axes in the fast budget; in the full
    // one (240 steps) 2 of 20 still do: another stage still rounds an absolute coordinate by
    // its sign (not found yet; documented limitation, asserted at its measured figure).
    Check(r, "across_axes_scenes_diverged", crossDiverged, budget == Budget::full ? 2 : 0, budget == Budget::full);
    Check(r, "transform_tie_diff_raw", static_cast<double>(TransformTieDifference()), 0);
}

}  // namespace lockbox::stability::detail
