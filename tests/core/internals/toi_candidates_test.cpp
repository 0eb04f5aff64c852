// The time-of-impact event search visits only its candidates (contacts with a cached time of
// impact or a fast body, in contact-list order) instead of every contact as 2.2.1 does. The
// events, and so every bit of every step, must be those of the full search: each scene runs
// twice, once with each search, and the worlds are compared after every frame.

#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "../../state/StateTestUtil.h"
#include "lockbox_internal/WorldInternals.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::DescribeDifference;
using testing_state::SceneRun;

#ifdef NDEBUG
constexpr int kFrameScale = 1;
#else
constexpr int kFrameScale = 4;  // sanitizer and debug builds are about ten times slower
#endif

struct Case {
    const char* scene;
    int frames;
    bool subStepping;
};

void ExpectSameAsFullSearch(const Case& c) {
    SceneRun reference(c.scene);
    SceneRun candidates(c.scene);
    ASSERT_TRUE(reference.scene && candidates.scene) << c.scene;
    test::SetToiSearchEveryContact(reference.world(), true);
    reference.world().SetSubStepping(c.subStepping);
    candidates.world().SetSubStepping(c.subStepping);
    for (int frame = 0; frame < c.frames / kFrameScale; ++frame) {
        reference.Advance();
        candidates.Advance();
        ASSERT_EQ(DescribeDifference(reference.world(), candidates.world()), "")
            << c.scene << (c.subStepping ? " (sub-stepping)" : "") << ", frame " << frame;
    }
    EXPECT_EQ(b2WorldHash(reference.world()), b2WorldHash(candidates.world()));
}

TEST(ToiCandidates, EventsAreThoseOfTheFullSearch) {
    for (const Case& c :
         {Case{"rain", 240, false}, Case{"bullet_wall_dynamic", 60, false}, Case{"bullet_wall_bullet", 60, false},
          Case{"bullet_stack_dynamic", 60, false}, Case{"bullet_stack_bullet", 60, false},
          Case{"pyramid20", 120, false}, Case{"one_sided_platform", 120, false}, Case{"ragdolls", 120, false}}) {
        ExpectSameAsFullSearch(c);
    }
}

// With sub-stepping a step solves one event and leaves the cached times of impact for the next:
// candidates then also come from a previous step.
TEST(ToiCandidates, SubSteppingKeepsTheFullSearchsEvents) {
    for (const Case& c :
         {Case{"bullet_wall_bullet", 60, true}, Case{"bullet_stack_bullet", 60, true}, Case{"rain", 120, true}}) {
        ExpectSameAsFullSearch(c);
    }
}

// Two cases the scenes rarely make, built to happen at the first step (zero gravity, 60 Hz). A
// bullet at 200 m/s moves 3.3 m a step.
struct Built {
    std::unique_ptr<b2World> world = std::make_unique<b2World>(b2Vec2(0, 0));
    b2Body* Static(b2Vec2 at, Fixed halfWidth, Fixed halfHeight) {
        b2BodyDef def;
        def.position = at;
        b2Body* body = world->CreateBody(&def);
        b2PolygonShape box;
        box.SetAsBox(halfWidth, halfHeight);
        body->CreateFixture(&box, 0);
        return body;
    }
    b2Body* Bullet(b2Vec2 at, b2Vec2 velocity) {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.bullet = true;
        def.position = at;
        def.linearVelocity = velocity;
        b2Body* body = world->CreateBody(&def);
        b2CircleShape circle;
        circle.m_radius = Fixed(0.1);
        b2FixtureDef fixture;
        fixture.shape = &circle;
        fixture.density = 1;
        fixture.restitution = 1;
        body->CreateFixture(&fixture);
        return body;
    }
};

// Steps two copies, one with each search, and compares them after every step.
void ExpectSameAsFullSearch(Built& reference, Built& candidates, int steps, const char* name) {
    test::SetToiSearchEveryContact(*reference.world, true);
    for (int i = 0; i < steps; ++i) {
        reference.world->Step(Fixed::FromRaw(1092), 8, 3);
        candidates.world->Step(Fixed::FromRaw(1092), 8, 3);
        ASSERT_EQ(DescribeDifference(*reference.world, *candidates.world), "") << name << ", step " << i;
    }
}

// On a tie the earlier contact in the list takes the event. Two bullets fly at two walls along
// mirrored paths, so their times of impact are equal; with sub-stepping a step solves one event
// only, and the other bullet ends the step past its wall. Made in the opposite order, the
// contacts' list order flips, and so does the bullet stopped.
TEST(ToiCandidates, TiesGoToTheEarlierContactInTheList) {
    const auto build = [](bool upperFirst) {
        Built b;
        b.Static(b2Vec2(1, upperFirst ? 5 : -5), Fixed(0.05), 1);
        b.Static(b2Vec2(1, upperFirst ? -5 : 5), Fixed(0.05), 1);
        b.Bullet(b2Vec2(0, upperFirst ? 5 : -5), b2Vec2(200, 0));
        b.Bullet(b2Vec2(0, upperFirst ? -5 : 5), b2Vec2(200, 0));
        b.world->SetSubStepping(true);
        return b;
    };
    std::vector<bool> upperStopped;
    for (const bool upperFirst : {true, false}) {
        Built reference = build(upperFirst), candidates = build(upperFirst);
        ExpectSameAsFullSearch(reference, candidates, 1, upperFirst ? "upper first" : "lower first");
        b2World& world = *candidates.world;
        // The first contact in the list between a bullet and a wall names the bullet stopped.
        b2Body* earlier = nullptr;
        for (b2Contact* c = world.GetContactList(); c && !earlier; c = c->GetNext()) {
            b2Body* a = c->GetFixtureA()->GetBody();
            b2Body* b = c->GetFixtureB()->GetBody();
            if (a->IsBullet() != b->IsBullet()) earlier = a->IsBullet() ? a : b;
        }
        ASSERT_NE(earlier, nullptr);
        int stopped = 0;
        for (b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
            if (!b->IsBullet()) continue;
            const bool before = b->GetPosition().x < Fixed(1);
            stopped += before ? 1 : 0;
            EXPECT_EQ(before, b == earlier) << (upperFirst ? "upper first" : "lower first");
        }
        EXPECT_EQ(stopped, 1);
        upperStopped.push_back(earlier->GetPosition().y > 0);
    }
    EXPECT_NE(upperStopped[0], upperStopped[1]) << "the times of impact were not tied";
}

// Small pyramids on an edge, as in many_pyramids: their bottom rows start pressed into the
// ground, and each step solves hundreds of events at once, from a queue of thousands of cached
// times of impact.
TEST(ToiCandidates, PressedPyramidsKeepTheFullSearchsEvents) {
    const auto build = [] {
        Built b;
        b.world->SetGravity(b2Vec2(0, -10));
        b2BodyDef groundDef;
        b2Body* ground = b.world->CreateBody(&groundDef);
        b2EdgeShape edge;
        edge.Set(b2Vec2(-40, 0), b2Vec2(40, 0));
        ground->CreateFixture(&edge, 0);
        b2PolygonShape box;
        box.SetAsBox(Fixed(0.5), Fixed(0.5));
        for (int p = 0; p < 6; ++p) {
            for (int i = 0; i < 10; ++i) {
                for (int j = i; j < 10; ++j) {
                    b2BodyDef def;
                    def.type = b2_dynamicBody;
                    def.position.Set(Fixed(-33 + 11 * p) + Fixed::FromRatio(i + 1, 2) + (j - i),
                                     Fixed::FromRatio(2 * i + 1, 2));
                    b.world->CreateBody(&def)->CreateFixture(&box, 1);
                }
            }
        }
        return b;
    };
    Built reference = build(), candidates = build();
    int events = 0;
    test::SetToiSearchEveryContact(*reference.world, true);
    for (int i = 0; i < 60 / kFrameScale; ++i) {
        reference.world->Step(Fixed::FromRaw(1092), 8, 3);
        candidates.world->Step(Fixed::FromRaw(1092), 8, 3);
        ASSERT_EQ(DescribeDifference(*reference.world, *candidates.world), "") << "step " << i;
        events += candidates.world->GetProfile().toiEvents;
    }
    EXPECT_GT(events, 60 / kFrameScale);
}

// The bullet bounces off the wall ahead and, later in the same step, reaches a wall behind its
// start: that contact is created by the sub-step's broad-phase update, and must be searched.
TEST(ToiCandidates, ContactCreatedBySubStepIsSearched) {
    auto build = [] {
        Built b;
        b.Static(b2Vec2(1, 0), Fixed(0.05), 1);
        b.Static(b2Vec2(-0.5, 0), Fixed(0.05), 1);
        b.Bullet(b2Vec2(0, 0), b2Vec2(200, 0));
        return b;
    };
    Built reference = build(), candidates = build();
    ExpectSameAsFullSearch(reference, candidates, 4, "bounce");
    // The bullet is still between the walls: the second wall's event was found.
    const Fixed x = candidates.world->GetBodyList()->GetPosition().x;
    EXPECT_GT(x, Fixed(-0.5));
    EXPECT_LT(x, Fixed(1));
}

// The bullet hits a light box resting near a wall; the sub-step makes the box fast, and its
// contact with the wall (whose bodies were both slow when the search began) must be searched.
TEST(ToiCandidates, ContactOfBodyMadeFastBySubStepIsSearched) {
    auto build = [] {
        Built b;
        b.Static(b2Vec2(Fixed(1.73), 0), Fixed(0.05), 1);
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position = b2Vec2(Fixed(1.5), 0);
        b2Body* box = b.world->CreateBody(&def);
        b2PolygonShape shape;
        shape.SetAsBox(Fixed(0.1), Fixed(0.1));
        box->CreateFixture(&shape, Fixed(0.05));
        b.Bullet(b2Vec2(0, 0), b2Vec2(200, 0));
        return b;
    };
    Built reference = build(), candidates = build();
    ExpectSameAsFullSearch(reference, candidates, 4, "push");
    // The box stopped at the wall instead of passing through it.
    for (b2Body* b = candidates.world->GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() == b2_dynamicBody && !b->IsBullet()) {
            EXPECT_LT(b->GetPosition().x, Fixed(1.73));
        }
    }
}

// A listener may disable a contact whose time of impact is cached and later enable it again,
// while the events of one step are solved: the full search skips it meanwhile and takes it
// again afterwards, with the time of impact it had. Three bullets reach their walls one after
// the other in the same step (at about 0.2, 0.4 and 0.7 of it: a bullet moves 2 m a step); the
// first touch disables the second bullet's contact, the third touch enables it.
struct ToggleSecond final : b2ContactListener {
    b2World* world = nullptr;
    b2Body* walls[3] = {};
    int toggles = 0;
    b2Contact* Second() const {
        for (b2Contact* c = world->GetContactList(); c; c = c->GetNext()) {
            if (c->GetFixtureA()->GetBody() == walls[1] || c->GetFixtureB()->GetBody() == walls[1]) return c;
        }
        return nullptr;
    }
    void BeginContact(b2Contact* contact) override {
        const b2Body* a = contact->GetFixtureA()->GetBody();
        const b2Body* b = contact->GetFixtureB()->GetBody();
        const bool first = a == walls[0] || b == walls[0];
        const bool third = a == walls[2] || b == walls[2];
        b2Contact* second = Second();
        if ((!first && !third) || second == nullptr) return;
        second->SetEnabled(third);
        ++toggles;
    }
};

TEST(ToiCandidates, ContactDisabledAndEnabledAgainByAListener) {
    struct Toggled {
        Built built;
        std::unique_ptr<ToggleSecond> listener = std::make_unique<ToggleSecond>();
    };
    const auto build = [] {
        Toggled c;
        c.listener->world = c.built.world.get();
        const Fixed wallX[3] = {Fixed(0.5), 1, Fixed(1.5)};
        for (int k = 0; k < 3; ++k) {
            c.listener->walls[k] = c.built.Static(b2Vec2(wallX[k], Fixed(4 * k)), Fixed(0.05), 1);
            c.built.Bullet(b2Vec2(0, Fixed(4 * k)), b2Vec2(200, 0));
        }
        c.built.world->SetContactListener(c.listener.get());
        return c;
    };
    Toggled reference = build(), candidates = build();
    ExpectSameAsFullSearch(reference.built, candidates.built, 3, "toggled");
    EXPECT_EQ(candidates.listener->toggles, 2);
    // The second bullet took its event after all: it did not pass its wall.
    for (b2Body* b = candidates.built.world->GetBodyList(); b; b = b->GetNext()) {
        if (b->IsBullet()) {
            EXPECT_LT(b->GetPosition().x, Fixed(1.5)) << "bullet at y " << b->GetPosition().y.ToDouble();
        }
    }
}

// The search drops a candidate that a filter rejects for the rest of the step (two non-bullet
// dynamic bodies, a sensor). A listener may still make such a contact acceptable while the
// events are solved, by SetBullet or SetSensor; the full search then takes it, so the short one
// must too. Here the first event (a bullet reaching a wall) runs the listener, which edits the
// contact of a fast body with a light box ahead of it.
enum class Edit { bullet, sensor };

struct EditOnFirstStaticTouch final : b2ContactListener {
    Edit edit;
    b2Body* fastBody = nullptr;
    b2Fixture* boxFixture = nullptr;
    bool done = false;
    explicit EditOnFirstStaticTouch(Edit e) : edit(e) {}
    void BeginContact(b2Contact* contact) override {
        const bool withStatic = contact->GetFixtureA()->GetBody()->GetType() == b2_staticBody ||
                                contact->GetFixtureB()->GetBody()->GetType() == b2_staticBody;
        if (done || !withStatic) return;
        done = true;
        if (edit == Edit::bullet) fastBody->SetBullet(true);
        if (edit == Edit::sensor) boxFixture->SetSensor(false);
    }
};

struct EditedCase {
    Built built;
    std::unique_ptr<EditOnFirstStaticTouch> listener;
    b2Body* fastBody = nullptr;
    b2Body* box = nullptr;
};

EditedCase BuildEdited(Edit edit) {
    EditedCase e;
    e.listener = std::make_unique<EditOnFirstStaticTouch>(edit);
    e.built.world->SetContactListener(e.listener.get());
    // The bullet reaches its wall at about a quarter of the step.
    e.built.Static(b2Vec2(1, 5), Fixed(0.05), 1);
    e.built.Bullet(b2Vec2(0, 5), b2Vec2(200, 0));
    // A body at 100 m/s (a bullet only for the sensor case) meets the box at about half of it.
    e.fastBody = e.built.Bullet(b2Vec2(0, -5), b2Vec2(100, 0));
    e.fastBody->SetBullet(edit == Edit::sensor);
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position = b2Vec2(1, -5);
    e.box = e.built.world->CreateBody(&def);
    b2PolygonShape shape;
    shape.SetAsBox(Fixed(0.05), 1);
    b2FixtureDef fixture;
    fixture.shape = &shape;
    fixture.density = Fixed(0.05);
    fixture.isSensor = edit == Edit::sensor;
    e.listener->fastBody = e.fastBody;
    e.listener->boxFixture = e.box->CreateFixture(&fixture);
    return e;
}

TEST(ToiCandidates, ListenerEditBringsBackADroppedCandidate) {
    for (const Edit edit : {Edit::bullet, Edit::sensor}) {
        const char* name = edit == Edit::bullet ? "SetBullet" : "SetSensor";
        EditedCase reference = BuildEdited(edit), candidates = BuildEdited(edit);
        ExpectSameAsFullSearch(reference.built, candidates.built, 2, name);
        EXPECT_TRUE(candidates.listener->done) << name;
        // The edited contact took its event: the fast body did not pass through the box.
        EXPECT_LT(candidates.fastBody->GetPosition().x, candidates.box->GetPosition().x) << name;
    }
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
