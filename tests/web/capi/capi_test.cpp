// The C API behind the JavaScript package, called natively: definitions in the word format
// the JavaScript side writes, errors for bad input instead of crashes, and the same world as
// the C++ API builds (so the sanitizer presets check the bindings too).
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "Bindings.h"
#include "lockbox/scenes/LockboxScenes.h"

using namespace lockbox;
using namespace lockbox::web;

// The C API (web/src), declared as JavaScript sees it.
extern "C" {
const char* lb_last_error();
int32_t lb_number_to_fixed(uint32_t lo, uint32_t hi, int32_t* out);
int32_t lb_fixed_ratio(int32_t num, int32_t den, int32_t* out);
int32_t lb_fixed_parse(const char* text, int32_t* out);
WebWorld* lb_world_create(int32_t gx, int32_t gy);
void lb_world_destroy(WebWorld* w);
int32_t lb_world_step(WebWorld* w, int32_t dt, int32_t vel, int32_t pos);
void lb_world_hash(WebWorld* w, int32_t* out);
int32_t lb_world_save(WebWorld* w);
const uint8_t* lb_world_bytes(WebWorld* w);
int32_t lb_world_restore(WebWorld* w, const uint8_t* bytes, int32_t size);
int32_t lb_world_list(WebWorld* w, int32_t which);
const int32_t* lb_world_results(WebWorld* w);
int32_t lb_world_take_events(WebWorld* w);
int32_t lb_world_query_aabb(WebWorld* w, int32_t lx, int32_t ly, int32_t ux, int32_t uy);
int32_t lb_world_ray_cast(WebWorld* w, int32_t x1, int32_t y1, int32_t x2, int32_t y2, int32_t mode);
int32_t lb_world_draw(WebWorld* w);
int32_t lb_body_create(WebWorld* w, const int32_t* words, int32_t count);
int32_t lb_body_destroy(WebWorld* w, int32_t id);
int32_t lb_body_state(WebWorld* w, int32_t id, int32_t* out);
int32_t lb_fixture_create(WebWorld* w, int32_t body, const int32_t* words, int32_t count);
int32_t lb_joint_create(WebWorld* w, const int32_t* words, int32_t count);
int32_t lb_joint_state(WebWorld* w, int32_t id, int32_t invDt, int32_t* out);
int32_t lb_joint_set(WebWorld* w, int32_t id, int32_t kind, int32_t a, int32_t b);
}

namespace LOCKBOX_TEST_FILE {

constexpr int32_t kOne = 65536;

// Builds a definition's words: a presence mask, then each field in table order.
class Words {
public:
    Words& Skip(int words = 1) {
        ++m_field;
        m_words.insert(m_words.end(), static_cast<size_t>(words), 0);
        return *this;
    }
    Words& Word(int32_t v) {
        m_mask |= 1u << m_field++;
        m_words.push_back(v);
        return *this;
    }
    Words& Pair(int32_t a, int32_t b) {
        m_mask |= 1u << m_field++;
        m_words.push_back(a);
        m_words.push_back(b);
        return *this;
    }
    Words& Points(const std::vector<int32_t>& xy) {
        m_mask |= 1u << m_field++;
        m_words.push_back(static_cast<int32_t>(xy.size() / 2));
        m_words.insert(m_words.end(), xy.begin(), xy.end());
        return *this;
    }
    /// The words with the mask in front (and a prefix, e.g. a joint type).
    std::vector<int32_t> Done(std::vector<int32_t> prefix = {}) const {
        prefix.push_back(static_cast<int32_t>(m_mask));
        prefix.insert(prefix.end(), m_words.begin(), m_words.end());
        return prefix;
    }

private:
    uint32_t m_mask = 0;
    int m_field = 0;
    std::vector<int32_t> m_words;
};

// A fixture: the material fields (only the density given), then the shape kind and fields.
std::vector<int32_t> FixtureWords(int32_t density, int32_t kind, const Words& shape) {
    std::vector<int32_t> w = Words().Skip().Skip().Word(density).Skip().Skip().Skip().Skip().Skip(2).Done();
    w.push_back(kind);
    const std::vector<int32_t> s = shape.Done();
    w.insert(w.end(), s.begin(), s.end());
    return w;
}

uint64_t Hash(WebWorld* w) {
    int32_t h[2];
    lb_world_hash(w, h);
    return GetU64(h[0], h[1]);
}

// pyramid20 through the C API, as the JavaScript test builds it.
WebWorld* Pyramid20() {
    WebWorld* w = lb_world_create(0, -10 * kOne);
    const int32_t ground = lb_body_create(w, nullptr, 0);
    EXPECT_GE(ground, 0);
    const std::vector<int32_t> edge = FixtureWords(0, 1, Words().Pair(-40 * kOne, 0).Pair(40 * kOne, 0));
    EXPECT_GE(lb_fixture_create(w, ground, edge.data(), static_cast<int32_t>(edge.size())), 0) << lb_last_error();
    const std::vector<int32_t> box = FixtureWords(5 * kOne, 3, Words().Word(kOne / 2).Word(kOne / 2));
    for (int i = 0; i < 20; ++i) {
        for (int j = i; j < 20; ++j) {
            const std::vector<int32_t> body =
                Words()
                    .Word(b2_dynamicBody)
                    .Pair((-112 + 9 * i + 18 * (j - i)) * kOne / 16, (12 + 20 * i) * kOne / 16)
                    .Done();
            const int32_t id = lb_body_create(w, body.data(), static_cast<int32_t>(body.size()));
            EXPECT_GE(id, 0) << lb_last_error();
            EXPECT_GE(lb_fixture_create(w, id, box.data(), static_cast<int32_t>(box.size())), 0) << lb_last_error();
        }
    }
    return w;
}

uint64_t NativePyramid20(int steps) {
    auto scene = scenes::MakeLockboxScene("pyramid20");
    scenes::LockboxEngine e;
    scenes::ConfigureWorld(e, scene->Info(), scenes::RunSettings{});
    scene->Build(e);
    for (int i = 0; i < steps; ++i) e.Step(60, 8, 3);
    return e.world().Hash();
}

TEST(WebCapi, Pyramid20MatchesTheSceneLibrary) {
    WebWorld* w = Pyramid20();
    for (int i = 0; i < 60; ++i) ASSERT_EQ(lb_world_step(w, 1092, 8, 3), 0);
    EXPECT_EQ(Hash(w), NativePyramid20(60));
    lb_world_destroy(w);
}

TEST(WebCapi, SaveRestoreRoundTripAndRefusal) {
    WebWorld* w = Pyramid20();
    for (int i = 0; i < 30; ++i) lb_world_step(w, 1092, 8, 3);
    const int32_t n = lb_world_save(w);
    ASSERT_GT(n, 0);
    const std::vector<uint8_t> image(lb_world_bytes(w), lb_world_bytes(w) + n);
    const uint64_t at30 = Hash(w);
    for (int i = 0; i < 30; ++i) lb_world_step(w, 1092, 8, 3);
    const uint64_t at60 = Hash(w);

    WebWorld* fresh = lb_world_create(0, 0);
    ASSERT_EQ(lb_world_restore(fresh, image.data(), n), 0) << lb_last_error();
    EXPECT_EQ(Hash(fresh), at30);
    for (int i = 0; i < 30; ++i) lb_world_step(fresh, 1092, 8, 3);
    EXPECT_EQ(Hash(fresh), at60);

    // A damaged image is refused with a reason, and the world keeps its state.
    std::vector<uint8_t> bad = image;
    bad[bad.size() / 2] ^= 0x5A;
    EXPECT_EQ(lb_world_restore(fresh, bad.data(), static_cast<int32_t>(bad.size())), -1);
    EXPECT_NE(std::string(lb_last_error()), "");
    EXPECT_EQ(Hash(fresh), at60);
    const uint8_t junk[3] = {1, 2, 3};
    EXPECT_EQ(lb_world_restore(fresh, junk, 3), -1);
    EXPECT_EQ(lb_world_restore(fresh, junk, -1), -1);
    lb_world_destroy(fresh);
    lb_world_destroy(w);
}

TEST(WebCapi, BadDefinitionsAreRefused) {
    WebWorld* w = lb_world_create(0, -10 * kOne);
    const std::vector<int32_t> badType = Words().Word(7).Done();
    EXPECT_EQ(lb_body_create(w, badType.data(), static_cast<int32_t>(badType.size())), -1);
    EXPECT_NE(std::string(lb_last_error()).find("type 7"), std::string::npos);
    // A mask announcing more fields than the words hold.
    const std::vector<int32_t> shortDef = {0x3FFF, 2, 0};
    EXPECT_EQ(lb_body_create(w, shortDef.data(), static_cast<int32_t>(shortDef.size())), -1);
    const int32_t body = lb_body_create(w, badType.data(), 0);  // no words: every default
    ASSERT_GE(body, 0);
    // Shapes: a collinear polygon, a box without size, a point list longer than the words,
    // an unknown shape kind.
    const std::vector<int32_t> collinear = FixtureWords(kOne, 2, Words().Points({0, 0, kOne, 0, 2 * kOne, 0}).Skip());
    EXPECT_EQ(lb_fixture_create(w, body, collinear.data(), static_cast<int32_t>(collinear.size())), -1);
    EXPECT_NE(std::string(lb_last_error()).find("polygon refused"), std::string::npos);
    const std::vector<int32_t> noSize = FixtureWords(kOne, 3, Words());
    EXPECT_EQ(lb_fixture_create(w, body, noSize.data(), static_cast<int32_t>(noSize.size())), -1);
    std::vector<int32_t> overlong = FixtureWords(kOne, 2, Words().Points({0, 0, kOne, 0, 0, kOne}));
    overlong[overlong.size() - 7] = 1000;  // the point count
    EXPECT_EQ(lb_fixture_create(w, body, overlong.data(), static_cast<int32_t>(overlong.size())), -1);
    const std::vector<int32_t> unknown = FixtureWords(kOne, 9, Words());
    EXPECT_EQ(lb_fixture_create(w, body, unknown.data(), static_cast<int32_t>(unknown.size())), -1);
    // Joints: unknown type, missing or equal bodies, a gear of non-gear joints, bad ids.
    const std::vector<int32_t> unknownJoint = Words().Done({42});
    EXPECT_EQ(lb_joint_create(w, unknownJoint.data(), static_cast<int32_t>(unknownJoint.size())), -1);
    const std::vector<int32_t> sameBody = Words().Word(body).Word(body).Done({e_revoluteJoint});
    EXPECT_EQ(lb_joint_create(w, sameBody.data(), static_cast<int32_t>(sameBody.size())), -1);
    const std::vector<int32_t> noBody = Words().Word(body).Word(99).Done({e_weldJoint});
    EXPECT_EQ(lb_joint_create(w, noBody.data(), static_cast<int32_t>(noBody.size())), -1);
    EXPECT_NE(std::string(lb_last_error()).find("no body with id 99"), std::string::npos);
    const int32_t other = lb_body_create(w, badType.data(), 0);
    const std::vector<int32_t> rope = Words().Word(body).Word(other).Done({e_ropeJoint});
    const int32_t ropeId = lb_joint_create(w, rope.data(), static_cast<int32_t>(rope.size()));
    ASSERT_GE(ropeId, 0) << lb_last_error();
    const std::vector<int32_t> gear =
        Words().Skip().Skip().Skip().Skip(2).Word(ropeId).Word(ropeId).Done({e_gearJoint});
    EXPECT_EQ(lb_joint_create(w, gear.data(), static_cast<int32_t>(gear.size())), -1);
    EXPECT_EQ(lb_joint_set(w, ropeId, 0, 1, 0), -1);  // a rope has no motor
    EXPECT_EQ(lb_body_destroy(w, 1234), -1);
    int32_t state[22];
    EXPECT_EQ(lb_body_state(w, -1, state), -1);
    EXPECT_EQ(lb_world_step(w, -1, 8, 3), -1);
    lb_world_destroy(w);
}

TEST(WebCapi, Numbers) {
    int32_t raw = 0;
    // 0.1 = 0x3FB999999999999A.
    EXPECT_EQ(lb_number_to_fixed(0x9999999Au, 0x3FB99999u, &raw), 0);
    EXPECT_EQ(raw, 6554);
    EXPECT_EQ(lb_number_to_fixed(0, 0x7FF80000u, &raw), 1);  // NaN
    EXPECT_EQ(lb_fixed_ratio(1, 60, &raw), 0);
    EXPECT_EQ(raw, 1092);
    EXPECT_EQ(lb_fixed_ratio(1, 0, &raw), -1);
    EXPECT_EQ(lb_fixed_ratio(40000, 1, &raw), -1);
    EXPECT_EQ(lb_fixed_ratio(-65535, 2, &raw), 0);
    EXPECT_EQ(raw, -65535 * 32768);
    EXPECT_EQ(lb_fixed_parse("-12.375", &raw), 0);
    EXPECT_EQ(raw, -811008);
    EXPECT_EQ(lb_fixed_parse("12x", &raw), -1);
}

TEST(WebCapi, QueriesEventsAndDrawing) {
    WebWorld* w = Pyramid20();
    for (int i = 0; i < 30; ++i) lb_world_step(w, 1092, 8, 3);
    // Begin events for the first contacts, one record of 7 words each.
    const int32_t events = lb_world_take_events(w);
    EXPECT_GT(events, 0);
    EXPECT_EQ(lb_world_take_events(w), 0);
    // Every box of the bottom row is in a box around it.
    EXPECT_GE(lb_world_query_aabb(w, -8 * kOne, 0, 16 * kOne, kOne), 20);
    EXPECT_EQ(lb_world_query_aabb(w, kOne, kOne, 0, 0), -1);
    // A ray straight down at x = 0 hits the top face of a box high in the stack.
    ASSERT_EQ(lb_world_ray_cast(w, 0, 30 * kOne, 0, -kOne, 0), 1);
    const int32_t* hit = lb_world_results(w);
    EXPECT_GT(hit[2], 10 * kOne);  // point y
    EXPECT_EQ(hit[4], kOne);       // normal (0, 1)
    EXPECT_GT(lb_world_ray_cast(w, -30 * kOne, kOne / 2, 30 * kOne, kOne / 2, 1), 1);
    EXPECT_EQ(lb_world_ray_cast(w, 0, 0, kOne, kOne, 5), -1);
    // 1 edge (4 + 1 + 2*2 words) and 210 boxes (4 + 1 + 4*2 words).
    EXPECT_EQ(lb_world_draw(w), 9 + 210 * 13);
    EXPECT_EQ(lb_world_list(w, 0), 211);
    lb_world_destroy(w);
}

}  // namespace LOCKBOX_TEST_FILE
