#pragma once
/// @file
/// What a scene file carries beside the physics: names, paths and custom properties of the
/// world, bodies, fixtures and joints, R.U.B.E.'s step settings, and the images. Loading fills
/// one; saving writes the one it is given. Objects are keyed by their ids (GetId(): small,
/// stable across snapshot and restore, never an address), so the metadata of a world survives
/// a rollback; an id freed by a destroy and reused by a new object carries the old entry until
/// it is changed or erased.
///
/// The lookups are b2dJson's (getBodyByName, getBodiesByCustomInt, ...). They take the world
/// and return its objects in ascending id order (creation order in a loaded world).

#include <map>
#include <string_view>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/scenefile/SceneDocument.h"

namespace lockbox::scenefile {

/// Names, paths, custom properties and images of one scene.
class LOCKBOX_API SceneMetadata {
public:
    /// The world's custom properties (its name and path are unused).
    ObjectInfo worldInfo;
    /// R.U.B.E.'s step settings from the file (zero: not given).
    StepSettings step;
    /// Image entries; ImageDesc::body holds the body's id (-1: none).
    std::vector<ImageDesc> images;

    /// The entry of an object, created empty when missing.
    ///@{
    ObjectInfo& Body(const b2Body& body) { return m_bodies[body.GetId()]; }
    ObjectInfo& Fixture(const b2Fixture& fixture) { return m_fixtures[fixture.GetId()]; }
    ObjectInfo& Joint(const b2Joint& joint) { return m_joints[joint.GetId()]; }
    ///@}
    /// The entry of an object, or nullptr.
    ///@{
    const ObjectInfo* FindBody(const b2Body& body) const { return Find(m_bodies, body.GetId()); }
    const ObjectInfo* FindFixture(const b2Fixture& fixture) const { return Find(m_fixtures, fixture.GetId()); }
    const ObjectInfo* FindJoint(const b2Joint& joint) const { return Find(m_joints, joint.GetId()); }
    ///@}
    /// Forgets an object (call when destroying it if its id may be reused).
    ///@{
    void EraseBody(const b2Body& body) { m_bodies.erase(body.GetId()); }
    void EraseFixture(const b2Fixture& fixture) { m_fixtures.erase(fixture.GetId()); }
    void EraseJoint(const b2Joint& joint) { m_joints.erase(joint.GetId()); }
    ///@}
    /// Forgets everything.
    void Clear();

    /// The name of an object ("" when it has none).
    ///@{
    std::string_view GetBodyName(const b2Body& body) const;
    std::string_view GetFixtureName(const b2Fixture& fixture) const;
    std::string_view GetJointName(const b2Joint& joint) const;
    ///@}

    /// The first object (lowest id) named `name`, or nullptr.
    ///@{
    b2Body* GetBodyByName(b2World& world, std::string_view name) const;
    b2Fixture* GetFixtureByName(b2World& world, std::string_view name) const;
    b2Joint* GetJointByName(b2World& world, std::string_view name) const;
    ///@}
    /// Every object named `name`, by ascending id.
    ///@{
    std::vector<b2Body*> GetBodiesByName(b2World& world, std::string_view name) const;
    std::vector<b2Fixture*> GetFixturesByName(b2World& world, std::string_view name) const;
    std::vector<b2Joint*> GetJointsByName(b2World& world, std::string_view name) const;
    ///@}

    /// The first object whose property `property` has the type and value of `value`.
    ///@{
    b2Body* GetBodyByCustom(b2World& world, std::string_view property, const CustomValue& value) const;
    b2Fixture* GetFixtureByCustom(b2World& world, std::string_view property, const CustomValue& value) const;
    b2Joint* GetJointByCustom(b2World& world, std::string_view property, const CustomValue& value) const;
    ///@}
    /// Every object whose property `property` has the type and value of `value`, by ascending id.
    ///@{
    std::vector<b2Body*> GetBodiesByCustom(b2World& world, std::string_view property, const CustomValue& value) const;
    std::vector<b2Fixture*> GetFixturesByCustom(b2World& world, std::string_view property,
                                                const CustomValue& value) const;
    std::vector<b2Joint*> GetJointsByCustom(b2World& world, std::string_view property, const CustomValue& value) const;
    ///@}

    /// Images named `name`, in file order.
    std::vector<const ImageDesc*> GetImagesByName(std::string_view name) const;

    /// Every entry by id (ascending), for iteration.
    ///@{
    const std::map<int32, ObjectInfo>& Bodies() const noexcept { return m_bodies; }
    const std::map<int32, ObjectInfo>& Fixtures() const noexcept { return m_fixtures; }
    const std::map<int32, ObjectInfo>& Joints() const noexcept { return m_joints; }
    ///@}

private:
    static const ObjectInfo* Find(const std::map<int32, ObjectInfo>& map, int32 id) {
        const auto it = map.find(id);
        return it == map.end() ? nullptr : &it->second;
    }

    std::map<int32, ObjectInfo> m_bodies;
    std::map<int32, ObjectInfo> m_fixtures;
    std::map<int32, ObjectInfo> m_joints;
};

}  // namespace lockbox::scenefile
