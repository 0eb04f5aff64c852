// SceneMetadata: b2dJson's lookups by name and by custom property, over ids.
#include "lockbox/scenefile/SceneMetadata.h"

namespace lockbox::scenefile {

namespace {

// Every live object of `map` (ascending id) accepted by `match`; `first` stops at one.
template <class T, class Get, class Match>
std::vector<T*> Collect(const std::map<int32, ObjectInfo>& map, Get&& get, Match&& match, bool first) {
    std::vector<T*> out;
    for (const auto& [id, info] : map) {
        if (!match(info)) continue;
        T* object = get(id);
        if (!object) continue;  // destroyed since
        out.push_back(object);
        if (first) break;
    }
    return out;
}

template <class T>
T* Front(const std::vector<T*>& v) {
    return v.empty() ? nullptr : v.front();
}

auto ByName(std::string_view name) {
    return [name](const ObjectInfo& info) { return info.name == name; };
}

auto ByCustom(std::string_view property, const CustomValue& value) {
    return [property, &value](const ObjectInfo& info) { return info.properties.Matches(property, value); };
}

}  // namespace

void SceneMetadata::Clear() {
    worldInfo = ObjectInfo();
    step = StepSettings();
    images.clear();
    m_bodies.clear();
    m_fixtures.clear();
    m_joints.clear();
}

std::string_view SceneMetadata::GetBodyName(const b2Body& body) const {
    const ObjectInfo* info = FindBody(body);
    return info ? std::string_view(info->name) : std::string_view();
}

std::string_view SceneMetadata::GetFixtureName(const b2Fixture& fixture) const {
    const ObjectInfo* info = FindFixture(fixture);
    return info ? std::string_view(info->name) : std::string_view();
}

std::string_view SceneMetadata::GetJointName(const b2Joint& joint) const {
    const ObjectInfo* info = FindJoint(joint);
    return info ? std::string_view(info->name) : std::string_view();
}

b2Body* SceneMetadata::GetBodyByName(b2World& world, std::string_view name) const {
    return Front(Collect<b2Body>(
        m_bodies, [&](int32 id) { return world.GetBody(id); }, ByName(name), true));
}

b2Fixture* SceneMetadata::GetFixtureByName(b2World& world, std::string_view name) const {
    return Front(Collect<b2Fixture>(
        m_fixtures, [&](int32 id) { return world.GetFixture(id); }, ByName(name), true));
}

b2Joint* SceneMetadata::GetJointByName(b2World& world, std::string_view name) const {
    return Front(Collect<b2Joint>(
        m_joints, [&](int32 id) { return world.GetJoint(id); }, ByName(name), true));
}

std::vector<b2Body*> SceneMetadata::GetBodiesByName(b2World& world, std::string_view name) const {
    return Collect<b2Body>(
        m_bodies, [&](int32 id) { return world.GetBody(id); }, ByName(name), false);
}

std::vector<b2Fixture*> SceneMetadata::GetFixturesByName(b2World& world, std::string_view name) const {
    return Collect<b2Fixture>(
        m_fixtures, [&](int32 id) { return world.GetFixture(id); }, ByName(name), false);
}

std::vector<b2Joint*> SceneMetadata::GetJointsByName(b2World& world, std::string_view name) const {
    return Collect<b2Joint>(
        m_joints, [&](int32 id) { return world.GetJoint(id); }, ByName(name), false);
}

b2Body* SceneMetadata::GetBodyByCustom(b2World& world, std::string_view property, const CustomValue& value) const {
    return Front(Collect<b2Body>(
        m_bodies, [&](int32 id) { return world.GetBody(id); }, ByCustom(property, value), true));
}

b2Fixture* SceneMetadata::GetFixtureByCustom(b2World& world, std::string_view property,
                                             const CustomValue& value) const {
    return Front(Collect<b2Fixture>(
        m_fixtures, [&](int32 id) { return world.GetFixture(id); }, ByCustom(property, value), true));
}

b2Joint* SceneMetadata::GetJointByCustom(b2World& world, std::string_view property, const CustomValue& value) const {
    return Front(Collect<b2Joint>(
        m_joints, [&](int32 id) { return world.GetJoint(id); }, ByCustom(property, value), true));
}

std::vector<b2Body*> SceneMetadata::GetBodiesByCustom(b2World& world, std::string_view property,
                                                      const CustomValue& value) const {
    return Collect<b2Body>(
        m_bodies, [&](int32 id) { return world.GetBody(id); }, ByCustom(property, value), false);
}

std::vector<b2Fixture*> SceneMetadata::GetFixturesByCustom(b2World& world, std::string_view property,
                                                           const CustomValue& value) const {
    return Collect<b2Fixture>(
        m_fixtures, [&](int32 id) { return world.GetFixture(id); }, ByCustom(property, value), false);
}

std::vector<b2Joint*> SceneMetadata::GetJointsByCustom(b2World& world, std::string_view property,
                                                       const CustomValue& value) const {
    return Collect<b2Joint>(
        m_joints, [&](int32 id) { return world.GetJoint(id); }, ByCustom(property, value), false);
}

std::vector<const ImageDesc*> SceneMetadata::GetImagesByName(std::string_view name) const {
    std::vector<const ImageDesc*> out;
    for (const ImageDesc& image : images) {
        if (image.info.name == name) out.push_back(&image);
    }
    return out;
}

}  // namespace lockbox::scenefile
