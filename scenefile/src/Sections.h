#pragma once
// The section loaders of ReadScene: each reads one kind of entry of the file into the
// document, validating as it goes (types, number ranges, the engine's shape checks), and
// returns false after recording the first error in the SceneReader.

#include "SceneReader.h"
#include "lockbox/scenefile/SceneDocument.h"

namespace lockbox::scenefile::detail {

/// One entry of "body", with its fixtures. `fixtureBudget` is what remains of
/// SceneLimits::maxFixtures; the body's fixtures are taken from it.
bool LoadBody(SceneReader& r, const JsonNode& n, const Path& path, int32& fixtureBudget, BodyDesc& out);

/// One entry of a body's "fixture": material, filter and exactly one shape.
bool LoadFixture(SceneReader& r, const JsonNode& n, const Path& path, FixtureDesc& out);

/// One entry of "joint". Body indices are checked against `bodyCount`; a gear joint's joint
/// indices are checked once every joint is read (CheckGearJoints).
bool LoadJoint(SceneReader& r, const JsonNode& n, const Path& path, int32 bodyCount, JointDesc& out);

/// Checks that every gear joint of `joints` names two revolute or prismatic joints of the list.
bool CheckGearJoints(SceneReader& r, const Path& jointsPath, const std::vector<JointDesc>& joints);

/// One entry of "image"; its body index is checked against `bodyCount` (-1: no body).
bool LoadImage(SceneReader& r, const JsonNode& n, const Path& path, int32 bodyCount, ImageDesc& out);

/// "index <i>, the file has <count> <plural>" (a reference error).
std::string IndexMessage(int64_t index, int64_t count, const char* plural);

/// Largest |angle| of a body or a joint's reference angle, rad: the revolute joint's continuous
/// angle range (kMaxContinuousAngle), so that differences of angles the joints form still fit.
inline constexpr Fixed kMaxFileAngle = 8192;
inline constexpr const char* kAngleWhy = "kMaxContinuousAngle";
/// Largest coordinate of a point given in a body's frame (joint anchors, the mass centre), m:
/// the shapes' own bound, so that a joint cannot reach farther from its body than a shape can.
inline constexpr const char* kLocalWhy = "b2_maxShapeCoordinate, in the body's frame";

}  // namespace lockbox::scenefile::detail
