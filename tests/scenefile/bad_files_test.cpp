// Bad scene files: each one (tests/scenefile/bad/) is refused with its expected one-line error,
// naming the JSON path and the problem, and a world it was loaded into is left exactly as it
// was (same hash, same counts). Limits are checked with small SceneLimits on good files.
#include <gtest/gtest.h>

#include "SceneFileTestUtil.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::scenefile::test {
namespace LOCKBOX_TEST_FILE {

struct BadFile {
    const char* file;     ///< in tests/scenefile/bad/
    SceneError error;     ///< the expected kind
    const char* message;  ///< the expected SceneResult::Describe()
};

const BadFile kBadFiles[] = {
    {"syntax", SceneError::e_syntax, "not JSON at byte 47: Invalid value."},
    {"not_an_object", SceneError::e_type, "expected an object, found an array"},
    {"nul_byte", SceneError::e_syntax, "not JSON at byte 14: a NUL byte"},
    // Ends inside a four-byte character: the encoding check must not read past the text.
    {"truncated_utf8", SceneError::e_syntax, "not JSON at byte 63: Invalid encoding in string."},
    {"too_deep", SceneError::e_limit, "nesting deeper than 32 arrays and objects"},
    {"duplicate_key", SceneError::e_syntax, "body[0].angle: the key appears twice"},
    {"body_not_array", SceneError::e_type, "body: expected an array, found an object"},
    {"body_type", SceneError::e_range, "body[0].type: 3 is out of range 0..2"},
    {"bad_hex", SceneError::e_number,
     "body[0].angle: \"12G4\" is not a number: give decimal text or 8 hexadecimal digits (a binary32's bits)"},
    {"hex_nan", SceneError::e_number, "body[0].angle: \"7FC00000\" is an infinite or NaN float"},
    {"beyond_q16", SceneError::e_number,
     "body[0].position.x: 40000 does not fit Q16.16 (magnitude at most 32767.99998)"},
    {"outside_bounds", SceneError::e_range,
     "body[0].position: (17000, 0) is outside the world bounds (-16000, -16000) to (16000, 16000)"},
    {"negative_damping", SceneError::e_range, "body[0].linearDamping: -1 is negative"},
    {"negative_mass", SceneError::e_range, "body[0].massData-mass: -2 is negative"},
    {"vector_number", SceneError::e_type,
     "body[0].position: expected a vector ({\"x\": ..., \"y\": ...}, or 0 for the zero vector), found the number 5"},
    {"bool_number", SceneError::e_type, "body[0].bullet: expected true or false, found a number"},
    {"polygon_nine", SceneError::e_shape, "body[3].fixture[1].polygon.vertices: 9 vertices, at most 8"},
    {"polygon_clockwise", SceneError::e_shape,
     "body[0].fixture[0].polygon.vertices: the polygon is clockwise; give the vertices counter-clockwise"},
    {"polygon_concave", SceneError::e_shape, "body[0].fixture[0].polygon.vertices: the polygon is not convex"},
    {"polygon_xy_counts", SceneError::e_type, "body[0].fixture[0].polygon.vertices: 4 x values and 3 y values"},
    {"polygon_normals", SceneError::e_shape,
     "body[0].fixture[0].polygon.normals[1]: (1, 0.1) is more than 1/64 from the normal (1, 0) of the edge"},
    {"circle_radius", SceneError::e_shape, "body[0].fixture[0].circle.radius: the circle radius must be positive"},
    {"no_shape", SceneError::e_type,
     "body[0].fixture[0]: a fixture needs a shape: \"circle\", \"polygon\", \"edge\" or \"chain\""},
    {"two_shapes", SceneError::e_type,
     "body[0].fixture[0]: a fixture has one shape, this one has \"circle\" and \"polygon\""},
    {"negative_density", SceneError::e_range, "body[0].fixture[0].density: -1 is negative"},
    {"filter_bits", SceneError::e_range, "body[0].fixture[0].filter-maskBits: 70000 is out of range 0..65535"},
    {"chain_duplicate", SceneError::e_shape,
     "body[0].fixture[0].chain.vertices: two vertices are closer than the weld distance"},
    {"edge_beyond_shape_range", SceneError::e_shape,
     "body[0].fixture[0].edge: a coordinate is beyond b2_maxShapeCoordinate (4096 m)"},
    {"joint_body_index", SceneError::e_reference, "joint[7].bodyB: index 40, the file has 12 bodies"},
    {"joint_unknown_type", SceneError::e_type,
     "joint[0].type: unknown joint type \"spring\" (revolute, prismatic, distance, pulley, mouse, gear, wheel, "
     "weld, friction, rope)"},
    {"joint_motor", SceneError::e_type,
     "joint[0].type: \"motor\" joints came with Box2D 2.3; lockbox has the joints of 2.2.1"},
    {"joint_no_type", SceneError::e_type, "joint[0]: a joint needs a \"type\""},
    {"joint_same_body", SceneError::e_reference,
     "joint[0].bodyB: bodyA and bodyB are both body 1; a joint joins two bodies"},
    {"gear_of_distance", SceneError::e_reference,
     "joint[2].joint1: joint 0 is a distance joint; a gear couples revolute and prismatic joints"},
    {"gear_index", SceneError::e_reference, "joint[1].joint2: index 5, the file has 2 joints"},
    {"prismatic_zero_axis", SceneError::e_range, "joint[0].localAxisA: the axis is the zero vector"},
    {"distance_frequency", SceneError::e_range, "joint[0].frequency: 40 Hz is outside the engine's range [0, 30]"},
    {"mouse_no_frequency", SceneError::e_range, "joint[0].frequency: 0 Hz is outside the engine's range (0, 30]"},
    {"pulley_ratio", SceneError::e_range, "joint[0].ratio: a pulley ratio must be positive"},
    {"revolute_limits", SceneError::e_range, "joint[0].lowerLimit: the lower limit is above the upper limit"},
    {"property_two_values", SceneError::e_type,
     "body[0].customProperties[0]: a custom property holds one value, this one has \"int\" and \"float\""},
    {"property_not_integer", SceneError::e_number, "body[0].customProperties[0].int: 1.5 is not an integer"},
    {"property_colour", SceneError::e_type, "customProperties[0].color: 3 channels, a colour has 4"},
    {"image_body_index", SceneError::e_reference, "image[0].body: index 2, the file has 2 bodies"},
    {"body_angle", SceneError::e_range, "body[0].angle: 9000 is beyond +-8192 rad (kMaxContinuousAngle)"},
    {"joint_anchor", SceneError::e_range,
     "joint[0].anchorA: (5000, 0) is beyond +-4096 m (b2_maxShapeCoordinate, in the body's frame)"},
    {"pulley_total", SceneError::e_range, "joint[0]: lengthA + ratio * lengthB does not fit Q16.16 (32767.99998 m)"},
    {"mouse_outside", SceneError::e_range,
     "joint[0].target: (20000, 0) is outside the world bounds (-16000, -16000) to (16000, 16000)"},
};

class BadFiles : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadFiles, RefusedWithItsMessageAndTheWorldUntouched) {
    const BadFile& bad = GetParam();
    const std::string path = TestPath("bad/") + bad.file + ".json";
    const std::string text = ReadText(path);
    ASSERT_FALSE(text.empty()) << path;

    auto built = BuildLibraryScene("pyramid20");
    ASSERT_TRUE(built);
    b2World& world = built->engine.world();
    world.Step(Fixed::FromRatio(1, 60), 8, 3);  // contacts and motion, not just a fresh build
    const uint64 before = b2WorldHash(world);
    const int32 bodies = world.GetBodyCount();

    SceneMetadata meta;
    const SceneResult r = LoadScene(text, world, &meta);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.error, bad.error) << SceneErrorName(r.error);
    EXPECT_EQ(r.Describe(), bad.message);
    EXPECT_EQ(b2WorldHash(world), before);
    EXPECT_EQ(world.GetBodyCount(), bodies);
    EXPECT_TRUE(meta.Bodies().empty() && meta.images.empty());

    SceneResult fresh;
    EXPECT_EQ(LoadSceneWorld(text, &fresh), nullptr);
    EXPECT_EQ(fresh.Describe(), bad.message);
}

INSTANTIATE_TEST_SUITE_P(Table, BadFiles, ::testing::ValuesIn(kBadFiles),
                         [](const auto& p) { return std::string(p.param.file); });

TEST(BadFiles, EveryFileIsInTheTable) {
    // A bad file added without an expected message would go untested.
    size_t files = 0;
    for (const BadFile& b : kBadFiles) files += ReadText(TestPath("bad/") + b.file + ".json").empty() ? 0 : 1;
    EXPECT_EQ(files, std::size(kBadFiles));
}

TEST(SceneLimits, CountsSizeAndValues) {
    auto built = BuildLibraryScene("pyramid20");
    ASSERT_TRUE(built);
    const std::string text = SaveScene(built->engine.world());
    SceneDocument doc;
    SceneLimits limits;
    limits.maxBodies = 100;
    SceneResult r = ReadScene(text, doc, limits);
    EXPECT_EQ(r.error, SceneError::e_limit);
    EXPECT_EQ(r.Describe(), "body: 211 bodies, at most 100");
    limits = SceneLimits();
    limits.maxFileBytes = 1000;
    r = ReadScene(text, doc, limits);
    EXPECT_EQ(r.Describe(), "the file has " + std::to_string(text.size()) + " bytes, at most 1000");
    limits = SceneLimits();
    limits.maxValues = 5000;
    EXPECT_EQ(ReadScene(text, doc, limits).Describe(), "more than 5000 JSON values");
    limits = SceneLimits();
    limits.maxFixtures = 150;
    EXPECT_EQ(ReadScene(text, doc, limits).Describe(), "body[150].fixture: more than 150 fixtures in the file");
    EXPECT_TRUE(ReadScene(text, doc));
}

TEST(SceneFile, MissingFileAndLockedWorld) {
    b2World world(b2Vec2(0, -10));
    const SceneResult r = LoadSceneFile(TestPath("bad/no_such_file.json"), world);
    EXPECT_EQ(r.error, SceneError::e_io);

    // Loading from inside a step (a contact callback) is refused: the world is locked.
    struct Loader : b2ContactListener {
        std::string text;
        SceneResult result;
        bool called = false;
        void BeginContact(b2Contact* c) override {
            if (called) return;
            called = true;
            result = LoadScene(text, *c->GetFixtureA()->GetBody()->GetWorld());
        }
    } loader;
    auto built = BuildLibraryScene("vertical_stack");
    ASSERT_TRUE(built);
    loader.text = SaveScene(built->engine.world());
    built->engine.world().SetContactListener(&loader);
    const int32 bodies = built->engine.world().GetBodyCount();
    for (int i = 0; i < 120 && !loader.called; ++i) built->engine.world().Step(Fixed::FromRatio(1, 60), 8, 3);
    ASSERT_TRUE(loader.called);
    EXPECT_EQ(loader.result.error, SceneError::e_locked) << loader.result.Describe();
    EXPECT_EQ(built->engine.world().GetBodyCount(), bodies);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::scenefile::test
